#pragma once
/// \file line_blend_kernels.hpp
/// Internal: the array work of a corner blend between two lines (the planner's common case) and the
/// record it fills, in two kernels (kernels/line_blend.cpp) compiled once per instruction set
/// (docs/simd.md). Everything here is 4 lanes wide, one lane per piece. No copy contracts to FMA, so
/// every instruction set gives the same bits. Only plain doubles and Vec3 cross between the kernels and
/// the rest of the library.

#include <limits>

#include "core/dispatch.hpp"
#include "netshape/core/types.hpp"
#include "netshape/motion/profile.hpp"
#include "netshape/motion/segment.hpp"

namespace netshape::motion::detail {

/// The frozen profile of piece k of a record of pieces (LineBlendRecord, CubicRecord: the arrays vs,
/// ve, vp, acc, t1..t3, d1..d3, dur): a trapezoid without windows.
template <class Record>
void frozen_profile(const Record& r, int k, Profile& p) noexcept {
  p.vs = r.vs[k];
  p.ve = r.ve[k];
  p.vp = r.vp[k];
  p.a = r.acc[k];
  p.j = std::numeric_limits<double>::infinity();
  p.t[0] = 0.0;
  p.t[1] = r.t1[k];
  p.t[2] = r.t2[k];
  p.t[3] = r.t3[k];
  p.t[4] = 0.0;
  p.d[0] = 0.0;
  p.d[1] = r.d1[k];
  p.d[2] = r.d2[k];
  p.d[3] = r.d3[k];
  p.d[4] = 0.0;
  p.duration = r.dur[k];
}

/// The pieces of a corner blend between two lines, kept once per blend by the planner.
/// Per piece: trims of the whole blend, length, speed cap, squared junction limit (piece 0: with the
/// cap before the blend), the reach w = min_i alpha_i·w0 + beta_i in squared speeds, the coefficients
/// of the peak squared speed min_i p1_i·(vs² + ve²) + p0_i and of the tangential budget
/// min_i (A_i − K_i·w)·iu_i (so that neither pass divides), the backward squared speed at its start,
/// and once frozen its trapezoid (speeds, acceleration, phase times and distances) and start time.
/// Every field is an array over the pieces (plain doubles, see the file comment).
struct LineBlendRecord {
  static constexpr int pieces = 4;
  int np = 0;      ///< pieces in use (1 or `pieces`)
  int cursor = 0;  ///< next piece to hand out (next_segment) or the piece being sampled (next)
  double trim_s[pieces] = {}, trim_e[pieces] = {}, len[pieces] = {}, vmax[pieces] = {};  ///< [mm], [mm/s]
  double w_junction[pieces] = {};  ///< squared junction limit at the piece's start [mm²/s²]
  double w_backward[pieces] = {};  ///< squared speed the backward pass allows at the piece's start [mm²/s²]
  // per axis i and piece k: [i][k]
  double alpha[3][pieces] = {}, beta[3][pieces] = {};
  double p1[3][pieces] = {}, p0[3][pieces] = {}, iu[3][pieces] = {}, K[3][pieces] = {};
  // frozen: speed-up, cruise, slow-down
  double vs[pieces] = {}, ve[pieces] = {}, vp[pieces] = {}, acc[pieces] = {};
  double t1[pieces] = {}, t2[pieces] = {}, t3[pieces] = {};
  double d1[pieces] = {}, d2[pieces] = {}, d3[pieces] = {};
  double dur[pieces] = {}, t0[pieces] = {};
  /// The frozen profile of piece k (a trapezoid without windows).
  void profile(int k, Profile& p) const noexcept { frozen_profile(*this, k, p); }
};

// Between two lines (symmetric blends, curvature peak at node 8) four pieces, narrower around the
// peak, given as the table node indices of the piece ends; they keep the blend rule's cycle time within
// 1.05 of the time-optimal one on the same path (bench/motion_plan.py).
constexpr int n_cuts_lines = LineBlendRecord::pieces;
constexpr int cuts_lines[n_cuts_lines + 1] = {0, 5, 8, 11, 16};
// lanes of the per-piece-end arrays: the n + 1 piece ends padded to whole AVX packets
constexpr int n_cut_lanes = (n_cuts_lines + 1 + 3) / 4 * 4;

/// What the kernels need at fixed parameter values, computed once (line_blend.cpp): with
/// a = (1 − u)², b = u², |B'|²/(9d²) = g2(u) = P + Q·c (P = a² + b², Q = 2ab) at the 3-point
/// Gauss-Legendre points of the first 8 table intervals (i, 8 + i, 16 + i: centre, left, right), at
/// the nodes 0..8 (with w = u·(1 − u)) and at the piece ends cuts_lines (padding lanes repeat node 16),
/// where also a and b. Plain arrays (see the file comment).
struct LineBlendTables {
  alignas(32) double gp[24], gq[24];
  alignas(32) double np[12], nq[12], w[12];  // nodes 0..8, padded
  alignas(32) double cp[n_cut_lanes], cq[n_cut_lanes], ca[n_cut_lanes], cb[n_cut_lanes], cw[n_cut_lanes];
  LineBlendTables();
};
const LineBlendTables& line_blend_tables();

/// The kernels of one instruction set.
struct LineBlendKernels {
  /// The symmetric blend P0 = V − d·u1, P1 = P2 = V, P3 = V + d·u2 between two lines (u1, u2 unit)
  /// into `whole` (the fields of Segment::blend, source `source`) and its pieces into `r`: trims,
  /// lengths, caps (|u_i|·v ≤ V_i, K_i·v² ≤ A_i, the feed vfeed), junction limits (piece 0: also
  /// v_prev, the cap before the blend), reach, peak and budget coefficients; w_backward = 0. A gentle
  /// turn (the centripetal part takes at most 2 % of the smallest A at full speed) is one piece.
  /// Returns the number of pieces. A, V: per-axis accelerations and velocities, inv_acc = 1/A.
  int (*build)(const LineBlendTables& T, Segment& whole, const Vec3& p0, const Vec3& vtx, const Vec3& p3,
               const Vec3& u1, const Vec3& u2, double d, long source, const Vec3& A, const Vec3& V,
               const Vec3& inv_acc, double vfeed, double v_prev, LineBlendRecord& r);
  /// Freeze the pieces of r one after the other from speed vs [mm/s], the piece after the blend
  /// allowing squared speed wt: trapezoids, and start times from t_start [s]. Returns the end speed.
  double (*freeze)(LineBlendRecord& r, double vs, double wt, const Vec3& A, double t_start);
  const char* isa;  ///< "baseline", "avx2" or "avx512"
};
NETSHAPE_SIMD_DECLARE(LineBlendKernels, line_blend_kernel_table)
/// The kernels of the instruction set chosen for this process (core/dispatch.hpp, NETSHAPE_ISA).
const LineBlendKernels& line_blend_kernels();
/// The baseline kernels (tests compare them with the chosen ones).
const LineBlendKernels& line_blend_kernels_plain();

}  // namespace netshape::motion::detail
