#pragma once
/// \file cubic_record_kernels.hpp
/// Internal: the record of the pieces of a cubic block (the planner's cubic-record nodes) and the array
/// work on it in kernels (kernels/cubic_record.cpp) compiled once per instruction set (docs/simd.md),
/// one lane per piece. No copy contracts to FMA, so every instruction set gives the same bits. Only the
/// record (plain doubles) and plain doubles cross between the kernels and the rest of the library.

#include "motion/planner/blend_bounds.hpp"
#include "core/dispatch.hpp"
#include "motion/kernels/line_blend_kernels.hpp"
#include "netshape/core/types.hpp"

namespace netshape::motion::detail {

/// The pieces of a cubic block held by one ring node (Geometry::cubic_record; only without jerk
/// limits), kept once per block by the planner. Per piece: its trims of the whole cubic and length,
/// largest curvature and |dκ/ds| (the output segment's), speed cap, squared junction limit, the reach
/// coefficients of both directions (PassRecord's alpha, beta, alpha_down, beta_down), the per-axis ramp
/// terms (Node::ramp_tangent, ramp_curvature) and, once frozen, its trapezoid (speeds, acceleration,
/// phase times and distances; no windows) and start time. Every field but w_after and the live axes is
/// an array over the pieces ([axis][piece], [direction][axis][piece]); the passes, the freeze and the
/// output run over them as over nodes of their own, with the same arithmetic.
struct CubicRecord {
  static constexpr int pieces = 16;
  int np = 0;      ///< pieces in use (1..pieces)
  int cursor = 0;  ///< next piece to hand out (next_segment) or the piece being sampled (next)
  double trim_start[pieces] = {}, trim_end[pieces] = {}, len[pieces] = {};  ///< [mm]
  double curvature[pieces] = {}, curvature_rate[pieces] = {};             ///< [1/mm], [1/mm²]
  double v_max[pieces] = {};                                              ///< [mm/s]
  double w_junction[pieces] = {};  ///< [mm²/s²]
  /// The squared speed after the last piece the backward pass last carried into the record [mm²/s²]
  /// (−1 before the first pass); the pieces' backward speeds are its chain of backward steps, found
  /// again where they are needed (the freeze) rather than stored by every pass
  double w_after = -1.0;
  /// The axes whose slowing-down term can bind on some piece, first `live_down` of live_down_axis: an
  /// axis with alpha_down ≥ 0 and beta_down ≥ w_junction on every piece never falls below the junction
  /// limit, so the backward step's minimum is the same without it (CubicRecordKernels::junctions)
  int live_down = 3;
  int live_down_axis[3] = {0, 1, 2};
  double alpha[3][pieces] = {}, beta[3][pieces] = {}, alpha_down[3][pieces] = {}, beta_down[3][pieces] = {};
  double ramp_u[2][3][pieces] = {}, ramp_k[2][3][pieces] = {};
  double u_abs[3][pieces] = {}, k_abs[3][pieces] = {};  ///< unsigned bounds (Node::tangent_bound, curvature_bound)
  // frozen: speed-up, cruise, slow-down
  double vs[pieces] = {}, ve[pieces] = {}, vp[pieces] = {}, acc[pieces] = {};
  double t1[pieces] = {}, t2[pieces] = {}, t3[pieces] = {};
  double d1[pieces] = {}, d2[pieces] = {}, d3[pieces] = {};
  double dur[pieces] = {}, t0[pieces] = {};
  /// The frozen profile of piece k.
  void profile(int k, Profile& p) const noexcept { frozen_profile(*this, k, p); }
  /// The ramp terms of piece k as a Node holds them (Node::ramp_tangent, Node::ramp_curvature).
  void ramps(int k, Vec3 (&Ua)[2], Vec3 (&Ka)[2]) const noexcept {
    for (int d = 0; d < 2; ++d)
      for (int i = 0; i < 3; ++i) {
        Ua[d][i] = ramp_u[d][i][k];
        Ka[d][i] = ramp_k[d][i][k];
      }
  }
};

/// The kernels of one instruction set.
struct CubicRecordKernels {
  /// The trapezoids of pieces [0, r.np) of r from their start and end speeds r.vs, r.ve (set), length,
  /// cap and ramp terms: PlannerState::axis_box_profile() without windows (peak squared speed and one
  /// tangential acceleration from the axis box, then the trapezoid) into r.vp, acc, t1..t3, d1..d3, dur.
  /// A: the per-axis acceleration limits (3), amin their smallest. Lanes past r.np (up to the next
  /// multiple of the lane count, at most CubicRecord::pieces) are computed from whatever they hold and
  /// written; nothing reads them.
  void (*freeze)(CubicRecord& r, const double* A, double amin);
  /// The speed caps and reach coefficients of pieces [0, r.np) from their lengths, unsigned bounds and
  /// ramp terms: set_limits()'s axis box (|u_i|·v ≤ V_i, K_i·v² ≤ A_i, the feed cap) into r.v_max and
  /// box_reach_both() into r.alpha, beta, alpha_down, beta_down. Returns the pieces (bit k for piece k)
  /// where a denominator of box_reach_both() is ≤ 0: their coefficients are to be set by
  /// set_box_reach() instead. V, A: per-axis velocity and acceleration limits (3). Lanes past r.np as
  /// for freeze.
  unsigned (*caps_reach)(CubicRecord& r, double feed_cap, const double* V, const double* A);
  /// The junction limits of pieces [0, r.np) (the first piece: min(v_corner, its cap)², the others:
  /// min(the cap before, its cap)²) into r.w_junction, then r.live_down and live_down_axis (after
  /// caps_reach and any set_box_reach()).
  void (*junctions)(CubicRecord& r, double v_corner);
  /// BlendBounds::bounds() and ramps() over each single table interval, for all 16 at once, into t's
  /// one_u, one_k, one_ua, one_ka (BlendBounds::single() reads them).
  void (*singles)(BlendBounds& t);
  /// Pieces [0, r.np) of r on the single table intervals r0, r0 + 1, ... (r0 + r.np ≤ 16): their
  /// bounds and ramp terms as singles() gives them (u_abs, k_abs, ramp_u, ramp_k) and piece_curvature()
  /// over their two nodes (curvature, curvature_rate) from the curvature k_at and arc length `table` at
  /// the 17 table nodes, straight into the record.
  void (*record_singles)(const BlendBounds& t, const double* k_at, const double* table, int r0, CubicRecord& r);
  /// BlendBounds::fill(): t's per-interval rows from the unit tangents T and curvature vectors Kv at the
  /// 17 table nodes (each 17 Vec3, as 51 doubles).
  void (*fill)(BlendBounds& t, const double* T, const double* Kv);
  /// For the cubic Bézier with control points P (P0..P3, 12 doubles): Segment::blend()'s arc-length
  /// table (17) and the curvature at the table nodes (k_at, 17; what finish_blend() reads), t's rows as
  /// fill() gives them from the node frames, and per axis c the left folds over all 16 intervals that
  /// BlendBounds::whole() takes (whole[c]: mu, du, tmax, tmin, st, then mk, dk, kmax, kmin, sk; max,
  /// the tmin and kmin rows min), and what finish_blend() sets from k_at and the table: the largest
  /// curvature and |dκ/ds| into finish[0], finish[1] (finish[0] = −1 where a value is not finite: the
  /// caller runs finish_blend()). Returns false, with nothing written, for a Bézier symmetric about
  /// u = 1/2 (a blend between two lines; Segment::blend() handles it).
  bool (*cubic_node)(const double* P, double* table, double* k_at, BlendBounds& t, double (*whole)[10],
                     double* finish);
  const char* isa;  ///< "baseline", "avx2" or "avx512"
};
NETSHAPE_SIMD_DECLARE(CubicRecordKernels, cubic_record_kernel_table)
/// The kernels of the instruction set chosen for this process (core/dispatch.hpp, NETSHAPE_ISA).
const CubicRecordKernels& cubic_record_kernels();
/// The baseline kernels (tests compare them with the chosen ones).
const CubicRecordKernels& cubic_record_kernels_plain();

}  // namespace netshape::motion::detail
