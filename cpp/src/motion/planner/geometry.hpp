#pragma once
/// \file geometry.hpp
/// Internal: the path geometry the planner bounds speeds with: points and tangents on the programmed
/// pieces, curvature vectors at segment ends, per-axis bounds over an arc window, the pieces an arc is
/// cut into (planner/geometry.cpp).

#include <algorithm>

#include "netshape/motion/segment.hpp"

namespace netshape::motion::detail {

/// Unit direction of a Bézier's end from its control points: P3 − P2, or P3 − P1 when P2 = P3, or
/// P3 − P0 (the derivative's direction at u = 1 where the first differences vanish).
inline Vec3 bezier_end_direction(const std::array<Vec3, 4>& c) {
  Vec3 d = c[3] - c[2];
  if (!(d.squaredNorm() > 0)) d = c[3] - c[1];
  if (!(d.squaredNorm() > 0)) d = c[3] - c[0];
  return d.normalized();
}
/// The same at the start (u = 0): P1 − P0, or P2 − P0, or P3 − P0.
inline Vec3 bezier_start_direction(const std::array<Vec3, 4>& c) {
  Vec3 d = c[1] - c[0];
  if (!(d.squaredNorm() > 0)) d = c[2] - c[0];
  if (!(d.squaredNorm() > 0)) d = c[3] - c[0];
  return d.normalized();
}
/// Unit tangent at the untrimmed end of a line, arc or blend.
inline Vec3 end_tangent(const Segment& s) {
  return s.kind == SegmentKind::blend ? bezier_end_direction(s.ctrl) : s.block.tangent_at(1.0);
}
/// Point at arc length `at` along the untrimmed programmed piece (line, arc, or a cubic block's
/// Bézier) [mm].
inline Vec3 piece_point(const Segment& s, double at) {
  if (s.kind == SegmentKind::line) return s.block.start + (at / s.full_length) * (s.block.end - s.block.start);
  if (s.kind == SegmentKind::blend) return bezier_point(s.ctrl, s.bezier_u(at));
  return s.block.point_at(std::clamp(at / s.full_length, 0.0, 1.0));
}
/// Unit tangent at arc length `at` along the untrimmed programmed piece (line, arc or Bézier).
inline Vec3 piece_tangent(const Segment& s, double at) {
  if (s.kind == SegmentKind::blend) {
    const double u = s.bezier_u(at);
    const Vec3 d = bezier_d1(s.ctrl, u);
    if (d.squaredNorm() > 0) return d.normalized();
    return u < 0.5 ? bezier_start_direction(s.ctrl) : bezier_end_direction(s.ctrl);
  }
  return s.block.tangent_at(std::clamp(at / s.full_length, 0.0, 1.0));
}

/// Curvature vector κ·n [1/mm] at the (trimmed) start or end of a segment (0 on lines).
Vec3 curvature_vector(const Segment& s, bool at_end);
/// Number of pieces an arc segment (its trimmed window) is cut into: pieces of at most
/// arc_piece_angle sweep, at most max_arc_pieces (planner/state.hpp).
int arc_piece_count(const Segment& s);
/// Per-axis bounds over the arc window [s0, s1] (arc length from the block start [mm]) of |u_i| (U)
/// and of the curvature vector |κ n_i| (K) [1/mm], a helix's curvature vector pointing to its axis; and
/// the per-direction terms (Ua, Ka: Node::ramp_tangent, ramp_curvature) from the signed ranges of u_i
/// and κ n_i over the window, each at most U, K (a spiral, whose radius changes, takes U, K).
void arc_bounds(const Segment& s, double s0, double s1, Vec3& U, Vec3& K, Vec3 (&Ua)[2], Vec3 (&Ka)[2]);

}  // namespace netshape::motion::detail
