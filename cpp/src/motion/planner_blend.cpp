// The blend rule's corner blends: the blend distance within the contour tolerance, the cubic Bézier
// cut into pieces at its arc-length table nodes with per-axis bounds for each piece, and the blend
// between two lines as one node whose pieces the line-blend kernels build (line_blend.hpp).
#include <algorithm>
#include <array>
#include <cmath>

#include "blend_bounds.hpp"
#include "planner_geometry.hpp"
#include "planner_state.hpp"

namespace netshape::motion::detail {

namespace {
// pieces of a corner blend, as runs of its 16 arc-length table intervals (node indices); between two
// lines without jerk limits: cuts_lines (line_blend.hpp)
const int cuts_general[max_blend_pieces + 1] = {0, 2, 4, 6, 8, 10, 12, 14, 16};
constexpr int n_cuts_general = 8;
const int cuts_jerk[5] = {0, 4, 8, 12, 16};
constexpr int n_cuts_jerk = 4;
const int cuts_one[2] = {0, 16};

}  // namespace

// P0 on the previous piece, P3 on the new block, both at distance d from the vertex: d starts at the
// distance whose deviation from two lines is the tolerance (at most 0.45 of either block) and is
// halved until the blend stays within the tolerance of the programmed pieces (always so between two
// lines). Then the previous node is trimmed, cut into pieces (arcs), and the blend's pieces appended;
// each piece has its own axis-box bounds, so the speed follows the curvature (the forward and backward
// passes over the pieces are the phase-plane method on a grid of stations).
void PlannerState::append_corner_blend(long first, Node& nn, const Vec3& u1, const Vec3& u2, double sin_half,
                                       long source) noexcept {
  const bool jerk_mode = jerk_limited_;
  const Segment& pseg = node(first).segment;  // the whole previous block (trim_start already final)
  const long psource = pseg.source;
  const bool lines = pseg.kind == SegmentKind::line && nn.segment.kind == SegmentKind::line;
  const double dmax = 0.45 * std::min(pseg.full_length, nn.segment.full_length);
  double d = std::min(dmax, 4.0 * blend_tolerance_ / sin_half);
  std::array<Vec3, 4> bl;
  for (int it = 0; it < 40; ++it) {
    const double sp = pseg.full_length - d;
    const Vec3 p0 = piece_point(pseg, sp), p3 = piece_point(nn.segment, d);
    if (lines) {  // the tangents are u1 and u2; the deviation bound is exact
      bl = {p0, p0 + d * u1, p3 - d * u2, p3};
      break;
    }
    const Vec3 t0 = piece_tangent(pseg, sp), t3 = piece_tangent(nn.segment, d);
    bl = {p0, p0 + d * t0, p3 - d * t3, p3};
    // the first pass of distance_to_piece over each programmed piece is the same for all 15 points
    Segment::PiecePolyline cp, cn;
    const bool pcurve = pseg.kind != SegmentKind::line, ncurve = nn.segment.kind != SegmentKind::line;
    if (pcurve) pseg.piece_polyline(sp, pseg.full_length, cp);
    if (ncurve) nn.segment.piece_polyline(0.0, d, cn);
    // the blend fits when each of the 15 points is within the tolerance of either piece (the test
    // max_i min(d_prev,i, d_next,i) ≤ tolerance, decided point by point: the next piece is measured
    // only when the previous one is too far, and the first point of neither fails the blend)
    const double tol = blend_tolerance_;
    bool fits = true;
    for (int i = 1; i < 16 && fits; ++i) {
      const Vec3 qp = bezier_point(bl, i / 16.0);
      fits = pseg.distance_to_piece(qp, sp, pseg.full_length, pcurve ? &cp : nullptr, tol) <= tol ||
             nn.segment.distance_to_piece(qp, 0.0, d, ncurve ? &cn : nullptr, tol) <= tol;
    }
    if (fits) break;
    d *= 0.5;
  }
  node(first).segment.trim_end = d;
  nn.segment.trim_start = d;
  split_last_block();
  const double vfeed = std::min(node(first).feed_cap, nn.feed_cap);
  double v_prev = node(tail_ - 1).v_max;
  if (lines && !jerk_mode) {  // the common case, built from scalar coefficients
    append_line_blend(source, psource, bl[0], pseg.block.end, bl[3], u1, u2, d, vfeed, v_prev);
    nn.v_corner = v_prev;
    nn.v_junction = std::min(nn.v_corner, nn.v_max);
    return;
  }
  std::array<Vec3, 17> T, Kv;
  Segment& whole = blend_geometry(source);
  whole = Segment::blend(bl[0], bl[1], bl[2], bl[3], psource, &T, &Kv);
  BlendBounds tab;
  cubic_record_kernels_->fill(tab, T[0].data(), Kv[0].data());
  // piece boundaries at table nodes
  const int* cut = jerk_mode ? cuts_jerk : cuts_general;
  int np = jerk_mode ? n_cuts_jerk : n_cuts_general;
  if (!jerk_mode) {
    Vec3 U, K;
    tab.bounds(0, 16, U, K);
    double vcap = vfeed;
    for (int i = 0; i < 3; ++i)
      if (U[i] > 0) vcap = std::min(vcap, limits_.velocity[i] / U[i]);
    // a gentle turn: the centripetal part takes little of the budget at full speed; one piece
    if (K.maxCoeff() * vcap * vcap <= 0.02 * limits_.acceleration.minCoeff()) {
      np = 1;
      cut = cuts_one;
    }
  }
  // jerk mode: where the blend meets an arc the curvature jumps (tangent junction); cap the speed
  // so the acceleration step's third difference takes at most half of J_i (see below)
  Vec3 dk0 = Vec3::Zero(), dk1 = Vec3::Zero();
  if (jerk_mode) {
    dk0 = Kv[0] - curvature_vector(node(tail_ - 1).segment, true);
    dk1 = curvature_vector(nn.segment, false) - Kv[16];
    if (dk0.norm() > 1e-12) {
      mark_curvature_step(node(tail_ - 1), false);
      update_pass(tail_ - 1);
    }
  }
  // what set_limits() finds for every piece of this blend (the same axes move on all of them)
  const double amin_blend = min_over_moving(limits_.acceleration, whole.moving_axes());
  for (int k = 0; k < np; ++k) {
    const int i0 = cut[k], i1 = cut[k + 1];
    // built in place in the ring (a Node is large: no temporary and copy)
    const std::size_t slot = ring_slot(tail_);
    Node& bn = nodes_[slot];
    // jerk mode: the node keeps the whole geometry; else it stays in the blend store
    init_blend_piece(bn, whole, i0, i1, source, vfeed, jerk_mode ? Geometry::in_node : Geometry::in_blend_store);
    tab.bounds(i0, i1, bn.tangent_bound, bn.curvature_bound);
    tab.ramps(i0, i1, bn.tangent_bound, bn.curvature_bound, bn.ramp_tangent, bn.ramp_curvature);
    bn.v_max = vfeed;
    if (jerk_mode) {
      piece_curvature(Kv, whole.table, i0, i1, bn.segment.curvature, bn.segment.curvature_rate);
      set_limits(bn);
    } else {
      // set_limits() on a curved piece without jerk limits: the per-axis box
      bn.bound = SpeedBound::axis_box;
      bn.path_jerk = inf;
      bn.path_accel = amin_blend;
      // min of the ratios with one division each, min of the roots = root of the min (one root)
      bn.v_max = std::min(bn.v_max, min_ratio(limits_.velocity.data(), bn.tangent_bound.data()));
      const double wk = min_ratio(limits_.acceleration.data(), bn.curvature_bound.data());
      if (wk < inf) bn.v_max = std::min(bn.v_max, std::sqrt(wk));
    }
    bn.v_junction = bn.v_corner = std::min(v_prev, bn.v_max);
    if (jerk_mode) {
      if (k == 0 && dk0.norm() > 1e-12) mark_curvature_step(bn, true);
      if (k + 1 == np && dk1.norm() > 1e-12) mark_curvature_step(bn, false);
      if (k == 0) bn.v_junction = bn.v_corner = std::min(bn.v_junction, curvature_step_speed(dk0));
    }
    v_prev = bn.v_max;
    PassRecord& x = passes_[slot];  // update_pass(tail_) with the slot known
    x.w_junction = bn.v_junction * bn.v_junction;
    x.length = planned_length(bn);
    x.path_accel = bn.path_accel;
    x.path_jerk = bn.path_jerk;
    set_reach(x, bn);
    x.w_backward = 0.0;
    x.line_blend = x.cubic = -1;
    ++tail_;
  }
  nn.v_corner = v_prev;
  if (jerk_mode && dk1.norm() > 1e-12) {
    nn.v_corner = std::min(nn.v_corner, curvature_step_speed(dk1));
    mark_curvature_step(nn, true);
  }
  nn.v_junction = std::min(nn.v_corner, nn.v_max);
}

// A blend piece over the table nodes i0..i1 of `whole`, written in place (a Node is large: no
// temporary and copy). Geometry::in_blend_store: the node keeps kind, trims, length, curvature and
// source only; else it holds the whole segment. Bounds, speeds and reach: the caller.
void PlannerState::init_blend_piece(Node& bn, const Segment& whole, int i0, int i1, long source, double vfeed,
                                    Geometry geometry) noexcept {
  if (geometry != Geometry::in_node) {
    bn.segment.kind = SegmentKind::blend;
    bn.segment.full_length = whole.full_length;
    bn.segment.curvature = whole.curvature;
    bn.segment.curvature_rate = whole.curvature_rate;
    bn.segment.source = whole.source;
  } else {
    bn.segment = whole;
  }
  bn.geometry = geometry;
  bn.segment.trim_start = whole.table[static_cast<std::size_t>(i0)];
  bn.segment.trim_end = whole.full_length - whole.table[static_cast<std::size_t>(i1)];
  bn.block = source;
  bn.feed_cap = vfeed;
  bn.start = bn.end = NodeEnd{};
  bn.extent = Extent::settled;
}

// The blend of a corner between two lines without jerk limits, cut into pieces at the table nodes
// cuts_lines (one piece for a gentle turn) and written as ONE node of the ring: the kernel fills the
// whole blend into the blend store and the pieces' trims, lengths, speed caps, reach coefficients
// (back_pass) and the coefficients of their peak speed and tangential budget (freeze_line_blend) into
// the line-blend record of the block, so neither pass divides. v_prev: the speed cap before the blend
// on entry, the cap of its last piece on return [mm/s].
void PlannerState::append_line_blend(long source, long psource, const Vec3& p0, const Vec3& vtx, const Vec3& p3,
                                     const Vec3& u1, const Vec3& u2, double d, double vfeed, double& v_prev) noexcept {
  const Vec3& A = limits_.acceleration;
  const std::size_t slot = ring_slot(tail_);
  const std::size_t ri = block_slot(source);
  LineBlendRecord& r = line_blends_[ri];
  Segment& whole = blends_[ri];
  const int np = line_blend_kernels_->build(*line_blend_tables_, whole, p0, vtx, p3, u1, u2, d, psource, A,
                                            limits_.velocity, inv_acceleration_, vfeed, v_prev, r);
  // the axes that move on the blend (Segment::moving_axes) and the smallest of their accelerations
  double amin_blend = inf;
  for (int i = 0; i < 3; ++i)
    if (std::abs(d * u1[i]) > 1e-12 || std::abs(d * u2[i]) > 1e-12) amin_blend = std::min(amin_blend, A[i]);
  if (!std::isfinite(amin_blend)) amin_blend = A.minCoeff();
  // one node for the whole blend, its pieces in the record
  Node& bn = nodes_[slot];
  init_blend_piece(bn, whole, 0, 16, source, vfeed, Geometry::line_blend_record);
  bn.bound = SpeedBound::axis_box;
  bn.path_jerk = inf;
  bn.path_accel = amin_blend;
  bn.v_junction = bn.v_corner = std::min(v_prev, r.vmax[0]);  // (its square is r.w_junction[0])
  v_prev = r.vmax[np - 1];
  bn.v_max = v_prev;
  PassRecord& x = passes_[slot];
  x.w_junction = r.w_junction[0];
  x.length = whole.full_length;
  x.path_accel = bn.path_accel;
  x.path_jerk = inf;
  x.w_backward = 0.0;
  x.bound = SpeedBound::axis_box;
  x.line_blend = static_cast<int>(ri);
  x.cubic = -1;
  ++tail_;
}

}  // namespace netshape::motion::detail
