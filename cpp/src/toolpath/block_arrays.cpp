// Structure-of-arrays tool path: conversion from and to blocks.
#include "netshape/toolpath/block_arrays.hpp"

namespace netshape::toolpath {

void BlockArrays::reserve(std::size_t n) {
  kind.reserve(n);
  start.reserve(3 * n);
  end.reserve(3 * n);
  center.reserve(3 * n);
  clockwise.reserve(n);
  plane.reserve(n);
  turns.reserve(n);
  feed.reserve(n);
  spindle_rpm.reserve(n);
  tool.reserve(n);
  line.reserve(n);
  dwell.reserve(n);
  dwell_after.reserve(n);
}

void BlockArrays::push_back(const Block& b, double dwell_before) {
  kind.push_back(static_cast<std::uint8_t>(b.kind));
  for (int c = 0; c < 3; ++c) start.push_back(b.start[c]);
  for (int c = 0; c < 3; ++c) end.push_back(b.end[c]);
  for (int c = 0; c < 3; ++c) center.push_back(b.center[c]);
  clockwise.push_back(b.clockwise ? 1 : 0);
  plane.push_back(static_cast<std::uint8_t>(b.plane));
  turns.push_back(b.turns);
  feed.push_back(b.feed);
  spindle_rpm.push_back(b.spindle_rpm);
  tool.push_back(b.tool);
  line.push_back(b.line);
  dwell.push_back(dwell_before);
  dwell_after.push_back(0.0);
}

Block BlockArrays::block(std::size_t i) const {
  Block b;
  b.kind = static_cast<MotionKind>(kind[i]);
  b.start = Vec3(start[3 * i], start[3 * i + 1], start[3 * i + 2]);
  b.end = Vec3(end[3 * i], end[3 * i + 1], end[3 * i + 2]);
  b.center = Vec3(center[3 * i], center[3 * i + 1], center[3 * i + 2]);
  b.clockwise = clockwise[i] != 0;
  b.plane = static_cast<Plane>(plane[i]);
  b.turns = turns[i];
  b.feed = feed[i];
  b.spindle_rpm = spindle_rpm[i];
  b.tool = tool[i];
  b.line = static_cast<long>(line[i]);
  return b;
}

BlockArrays BlockArrays::from_blocks(const std::vector<Block>& blocks) {
  BlockArrays a;
  a.reserve(blocks.size());
  for (const Block& b : blocks) a.push_back(b);
  return a;
}

std::vector<Block> BlockArrays::to_blocks() const {
  std::vector<Block> out;
  out.reserve(size());
  for (std::size_t i = 0; i < size(); ++i) out.push_back(block(i));
  return out;
}

}  // namespace netshape::toolpath
