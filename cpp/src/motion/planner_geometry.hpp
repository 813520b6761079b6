#pragma once
/// \file planner_geometry.hpp
/// Internal: the path geometry the planner bounds speeds with: points and tangents on the programmed
/// pieces, curvature vectors at segment ends, per-axis bounds over an arc window, the pieces an arc is
/// cut into (planner_geometry.cpp).

#include <algorithm>

#include "netshape/motion/segment.hpp"

namespace netshape::motion::detail {

/// Unit tangent at the end of a line, arc or blend.
inline Vec3 end_tangent(const Segment& s) {
  return s.kind == SegmentKind::blend ? Vec3((s.ctrl[3] - s.ctrl[2]).normalized()) : s.block.tangent_at(1.0);
}
/// Point at arc length `at` along the untrimmed programmed piece (line or arc) [mm].
inline Vec3 piece_point(const Segment& s, double at) {
  if (s.kind == SegmentKind::line) return s.block.start + (at / s.full_length) * (s.block.end - s.block.start);
  return s.block.point_at(std::clamp(at / s.full_length, 0.0, 1.0));
}
/// Unit tangent at arc length `at` along the untrimmed programmed piece (line or arc).
inline Vec3 piece_tangent(const Segment& s, double at) {
  return s.block.tangent_at(std::clamp(at / s.full_length, 0.0, 1.0));
}

/// Curvature vector κ·n [1/mm] at the start or the end of a segment (0 on lines).
Vec3 curvature_vector(const Segment& s, bool at_end);
/// Number of pieces an arc segment (its trimmed window) is cut into: pieces of at most
/// arc_piece_angle sweep, at most max_arc_pieces (planner_state.hpp).
int arc_piece_count(const Segment& s);
/// Per-axis bounds over the arc window [s0, s1] (arc length from the block start [mm]) of |u_i| (U)
/// and of the curvature vector |κ n_i| (K) [1/mm]; a helix's curvature vector points to its axis.
void arc_bounds(const Segment& s, double s0, double s1, Vec3& U, Vec3& K);

}  // namespace netshape::motion::detail
