// Whole-program figures (Summary), exact arc bounding boxes and arc chording.
#include "netshape/toolpath/toolpath.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "netshape/core/error.hpp"
#include "netshape/toolpath/gcode_reader.hpp"

namespace netshape::toolpath {

int chord_count(double radius, double sweep, double tol) {
  NETSHAPE_CHECK(std::isfinite(tol) && tol > 0.0, "chord_tolerance", tol, "must be a positive number [mm]");
  NETSHAPE_CHECK_FINITE("radius", radius);
  NETSHAPE_CHECK_FINITE("sweep", sweep);
  const double r = std::abs(radius);
  const double s = std::abs(sweep);
  if (r == 0.0 || s == 0.0) return 1;
  // A chord spanning the angle θ deviates r·(1 − cos(θ/2)) from the arc. When the radius is within
  // the tolerance every chord is, and a chord spans a quarter turn (a small full circle keeps its
  // four quadrant points).
  const double theta = tol >= r ? 0.5 * pi : 2.0 * std::acos(1.0 - tol / r);
  const double n = std::ceil(s / theta * (1.0 - 1e-12));
  NETSHAPE_CHECK(n <= 1e7, "chord_tolerance", tol,
                 "too small for this arc: more than 10 million chords would be needed [mm]");
  return std::max(1, static_cast<int>(n));
}

bool continues_run(const Vec3& a, const Vec3& b, const Vec3& c, double tolerance) noexcept {
  const Vec3 ab = b - a;
  const double lab = ab.norm();
  return lab > 0.0 && ab.dot(c - b) > 0.0 && ab.cross(c - a).norm() / lab <= tolerance;
}

void split_block(const Block& b, double chord_tolerance, std::vector<Block>& out) {
  if (b.kind != MotionKind::arc) {
    out.push_back(b);
    return;
  }
  const PlaneAxes ax = plane_axes(b.plane);
  const double r1 = std::hypot(b.end[ax.a] - b.center[ax.a], b.end[ax.b] - b.center[ax.b]);
  const int n = chord_count(std::max(b.radius(), r1), b.sweep(), chord_tolerance);
  Block c = b;
  c.kind = MotionKind::line;
  c.center = Vec3::Zero();
  c.clockwise = false;
  c.turns = 1;
  Vec3 prev = b.start;
  for (int i = 1; i <= n; ++i) {
    c.start = prev;
    c.end = i == n ? b.end : b.point_at(static_cast<double>(i) / n);
    out.push_back(c);
    prev = c.end;
  }
}

Toolpath Toolpath::split_arcs(double chord_tolerance) const {
  NETSHAPE_CHECK(std::isfinite(chord_tolerance) && chord_tolerance > 0.0, "chord_tolerance", chord_tolerance,
                 "must be a positive number [mm]");
  std::vector<Block> out;
  std::vector<long> origin;
  out.reserve(blocks.size());
  origin.reserve(blocks.size());
  for (std::size_t i = 0; i < blocks.size(); ++i) {
    split_block(blocks[i], chord_tolerance, out);
    origin.resize(out.size(), static_cast<long>(i));
  }
  return with_blocks(std::move(out), origin);
}

Toolpath Toolpath::with_blocks(std::vector<Block> new_blocks, const std::vector<long>& origin) const {
  NETSHAPE_CHECK(origin.size() == new_blocks.size(), "origin", origin.size(),
                 ("must have one entry per new block (" + std::to_string(new_blocks.size()) + ")").c_str());
  const long n = static_cast<long>(blocks.size());
  for (std::size_t i = 0; i < origin.size(); ++i) {
    NETSHAPE_CHECK(origin[i] >= 0 && origin[i] < n, "origin", origin[i],
                   ("must index a block of the tool path (0 … " + std::to_string(n - 1) + ")").c_str());
    NETSHAPE_CHECK(i == 0 || origin[i] >= origin[i - 1], "origin", origin[i], "must be non-decreasing");
  }
  Toolpath t;
  t.source = source;
  t.dwell_time = dwell_time;
  t.dwells = dwells;
  t.work_offsets = work_offsets;
  t.warnings = warnings;
  t.commands = commands;
  // first[k]: index of the first new block that came from old block k or a later one
  std::vector<std::size_t> first(blocks.size() + 1, new_blocks.size());
  for (std::size_t i = origin.size(); i-- > 0;) first[static_cast<std::size_t>(origin[i])] = i;
  for (std::size_t k = blocks.size(); k-- > 0;) first[k] = std::min(first[k], first[k + 1]);
  for (Command& c : t.commands) c.before = first[std::min(c.before, blocks.size())];
  t.blocks = std::move(new_blocks);
  return t;
}

void block_bounds(const Block& b, Vec3& lo, Vec3& hi) {
  lo = b.start.cwiseMin(b.end);
  hi = b.start.cwiseMax(b.end);
  if (b.kind != MotionKind::arc) return;
  const PlaneAxes ax = plane_axes(b.plane);
  const double sw = b.sweep();
  const double aw = std::abs(sw);
  if (aw == 0.0) return;
  const double a0 = std::atan2(b.start[ax.b] - b.center[ax.b], b.start[ax.a] - b.center[ax.a]);
  const double two_pi = 2.0 * pi;
  // The in-plane extremes lie where the angle crosses a multiple of π/2. The radius changes linearly
  // with the angle (spiral arcs), so the first and last crossing of each direction bound all others.
  for (int q = 0; q < 4; ++q) {
    const double phi = q * 0.5 * pi;
    double d = sw > 0.0 ? phi - a0 : a0 - phi;
    d = std::fmod(d, two_pi);
    if (d < 0.0) d += two_pi;
    if (d > aw) continue;
    const double t_first = d / aw;
    const double t_last = (d + std::floor((aw - d) / two_pi) * two_pi) / aw;
    for (double t : {t_first, t_last}) {
      const Vec3 p = b.point_at(std::min(t, 1.0));
      lo = lo.cwiseMin(p);
      hi = hi.cwiseMax(p);
    }
  }
}

void SummaryBuilder::add(const Block& b) {
  Vec3 lo, hi;
  block_bounds(b, lo, hi);
  if (empty_) {
    s_.bbox_min = lo;
    s_.bbox_max = hi;
    empty_ = false;
  } else {
    s_.bbox_min = s_.bbox_min.cwiseMin(lo);
    s_.bbox_max = s_.bbox_max.cwiseMax(hi);
  }
  const double len = b.length();
  switch (b.kind) {
    case MotionKind::rapid:
      ++s_.rapids;
      s_.rapid_length += len;
      return;
    case MotionKind::line: ++s_.lines; break;
    case MotionKind::arc: ++s_.arcs; break;
  }
  s_.feed_length += len;
  if (len > 0.0) {
    NETSHAPE_CHECK(b.feed > 0.0 && std::isfinite(b.feed), "block.feed", b.feed,
                   "a feed move needs a positive feed [mm/s]");
    s_.feed_time += len / b.feed;
  }
}

void SummaryBuilder::add_dwell(double seconds, long count) {
  NETSHAPE_CHECK(std::isfinite(seconds) && seconds >= 0.0, "dwell", seconds, "must be a non-negative time [s]");
  s_.dwell_time += seconds;
  s_.dwells += count;
}

Summary Toolpath::summary() const {
  SummaryBuilder sb;
  for (const Block& b : blocks) sb.add(b);
  sb.add_dwell(dwell_time, dwells);
  return sb.summary();
}

}  // namespace netshape::toolpath
