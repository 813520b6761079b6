#pragma once
/// \file blend_bounds.hpp
/// Internal: per-axis bounds of a cubic Bézier's unit tangent and curvature vector over runs of its
/// arc-length table intervals, unsigned (the speed caps) and signed (the acceleration terms of each
/// direction of a speed change); the planner's corner blends (planner/blend.cpp) and cubic blocks
/// (planner/cubic.cpp) bound each of their pieces with them.

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <limits>

#include "core/simd.hpp"
#include "netshape/core/types.hpp"

namespace netshape::motion::detail {

// A piece over the table nodes i0..i1 in jerk mode: its largest curvature |κ| at those nodes and the
// largest |Δ|κ| / Δs| between neighbouring ones (table: the arc lengths of the nodes).
// (k: |κ| at the nodes, Kv[i].norm())
inline void piece_curvature(const double (&k)[17], const std::array<double, 17>& table, int i0, int i1, double& kmax,
                            double& rate) noexcept {
  kmax = rate = 0;
  for (int i = i0; i <= i1; ++i) {
    const auto ii = static_cast<std::size_t>(i);
    kmax = std::max(kmax, k[ii]);
    if (i > i0 && table[ii] > table[ii - 1]) rate = std::max(rate, std::abs(k[ii] - k[ii - 1]) / (table[ii] - table[ii - 1]));
  }
}
inline void piece_curvature(const std::array<Vec3, 17>& Kv, const std::array<double, 17>& table, int i0, int i1,
                            double& kmax, double& rate) noexcept {
  double k[17];
  for (int i = i0; i <= i1; ++i) k[i] = Kv[static_cast<std::size_t>(i)].norm();
  piece_curvature(k, table, i0, i1, kmax, rate);
}

// The per-axis terms of one axis for both directions of a speed change (BlendBounds::ramps) from the
// signed ranges of u_i ([tn, tx]) and κn_i ([kn, kx]) over a piece, each term at most the unsigned
// bounds Uabs, Kabs.
inline void ramp_terms(double tx, double tn, double kx, double kn, double Uabs, double Kabs, double (&U)[2],
                       double (&K)[2]) noexcept {
  // sides (U, K): speeding up (tx, kx), (−tn, −kn); slowing down (−tn, kx), (tx, −kn). A side counts
  // when its U is > 0; the term is the larger U and the larger K of the sides that count (0, 0 if
  // none). Both sides count for both directions when tx > 0 and tn < 0: then both directions get
  // max(tx, −tn) and max(kx, −kn). (The maxima as (a < b) ? b : a, std::max's result.)
  const bool up = tx > 0, down = -tn > 0;
  double u0, k0, u1, k1;
  if (up && down) {
    u0 = u1 = tx < -tn ? -tn : tx;
    k0 = k1 = kx < -kn ? -kn : kx;
  } else if (up) {
    u0 = u1 = tx;
    k0 = kx;
    k1 = -kn;
  } else if (down) {
    u0 = u1 = -tn;
    k0 = -kn;
    k1 = kx;
  } else {
    u0 = u1 = k0 = k1 = 0.0;
  }
  U[0] = Uabs < u0 ? Uabs : u0;
  U[1] = Uabs < u1 ? Uabs : u1;
  K[0] = Kabs < k0 ? Kabs : k0;
  K[1] = Kabs < k1 ? Kabs : k1;
}

// Per-axis bounds of a blend's unit tangent |u_i| (U) and curvature vector |κ n_i| (K) over runs of
// its 17 table nodes, with a margin for what lies between the nodes (a quarter of the largest second
// difference of the node values, twice the parabolic estimate). The raw maxima are taken once per
// table interval; a run's bound is the max over its intervals (max is exact, so the bounds of the
// whole blend equal those computed over all nodes at once).
//
// Signed: per table interval the largest and smallest u_i and κn_i at its two nodes, widened by the
// same kind of margin from the second differences of the signed values. ramps() turns them into the
// per-axis terms of the axis box for each direction of a speed change (see there). The rows per
// interval are filled from the node values by the cubic-record kernel CubicRecordKernels::fill
// (kernels/cubic_record.cpp).
struct BlendBounds {
  // per axis c and table interval r (axis-major, so the loops over the nodes run on contiguous rows)
  double mu[3][16], mk[3][16], du[3][16], dk[3][16];  // raw maxima per table interval
  double tmax[3][16], tmin[3][16], kmax[3][16], kmin[3][16];  // signed extremes per interval
  double st[3][16], sk[3][16];  // largest second difference of the signed values per interval
  // bounds() and ramps() of each table interval alone, [axis][interval] (the cubic-record kernel
  // CubicRecordKernels::singles fills them)
  double one_u[3][16], one_k[3][16], one_ua[3][16], one_ka[2][3][16];
  // Per-axis terms over the table intervals [r0, r1) for a speed change along the path: dir 0 speeding
  // up (path acceleration a ≥ 0), dir 1 slowing down. On the piece u_i·a + κn_i·v² lies in [−A_i, A_i]
  // when |κn_i|·v² ≤ A_i (the speed cap from bounds()) and Uₐ_i·|a| + Kₐ_i·v² ≤ A_i: of the two sides
  // of the box, for a ≥ 0 the upper one holds when max(u_i)·a + max(κn_i)·v² ≤ A_i and the lower one
  // when max(−u_i)·a + max(−κn_i)·v² ≤ A_i (for a ≤ 0 the tangential parts swap). A side whose
  // tangential part is ≤ 0 on the whole piece needs only the speed cap. The sides that remain are
  // merged into one term per axis (the larger U and K); U, K of bounds() (passed in) bound them too,
  // so each term is at most the unsigned one. K may be negative: the centripetal part then eases the
  // axis, most at the highest speed (the passes and the freeze take the lowest speed for it).
  void ramps(int r0, int r1, const Vec3& Uabs, const Vec3& Kabs, Vec3 (&Ua)[2], Vec3 (&Ka)[2]) const noexcept {
    for (int c = 0; c < 3; ++c) {
      double tx = tmax[c][r0], tn = tmin[c][r0], kx = kmax[c][r0], kn = kmin[c][r0], e = st[c][r0],
             f = sk[c][r0];
      for (int r = r0 + 1; r < r1; ++r) {
        tx = std::max(tx, tmax[c][r]);
        tn = std::min(tn, tmin[c][r]);
        kx = std::max(kx, kmax[c][r]);
        kn = std::min(kn, kmin[c][r]);
        e = std::max(e, st[c][r]);
        f = std::max(f, sk[c][r]);
      }
      ramps_from(c, tx, tn, kx, kn, e, f, Uabs, Kabs, Ua, Ka);
    }
  }
  // ramps() of axis c from the extremes over the intervals: of u_c (tx, tn), of κn_c (kx, kn) and the
  // largest second differences e, f
  static void ramps_from(int c, double tx, double tn, double kx, double kn, double e, double f, const Vec3& Uabs,
                         const Vec3& Kabs, Vec3 (&Ua)[2], Vec3 (&Ka)[2]) noexcept {
    tx = std::min(1.0, tx + 0.25 * e + 1e-12);
    tn = std::max(-1.0, tn - 0.25 * e - 1e-12);
    kx = kx * (kx > 0 ? 1.0 + 1e-9 : 1.0 - 1e-9) + 0.25 * f;
    kn = kn * (kn < 0 ? 1.0 + 1e-9 : 1.0 - 1e-9) - 0.25 * f;
    double U[2], K[2];
    ramp_terms(tx, tn, kx, kn, Uabs[c], Kabs[c], U, K);
    for (int d = 0; d < 2; ++d) {
      Ua[d][c] = U[d];
      Ka[d][c] = K[d];
    }
  }
  // bounds over the table intervals [r0, r1)
  void bounds(int r0, int r1, Vec3& U, Vec3& K) const noexcept {
    for (int c = 0; c < 3; ++c) {
      double a = mu[c][r0], b = mk[c][r0], e = du[c][r0], f = dk[c][r0];
      for (int r = r0 + 1; r < r1; ++r) {
        a = std::max(a, mu[c][r]);
        b = std::max(b, mk[c][r]);
        e = std::max(e, du[c][r]);
        f = std::max(f, dk[c][r]);
      }
      bounds_from(c, a, b, e, f, U, K);
    }
  }
  // bounds() of axis c from the raw maxima over the intervals (a: |u_c|, b: |κn_c|, e, f: their second
  // differences)
  static void bounds_from(int c, double a, double b, double e, double f, Vec3& U, Vec3& K) noexcept {
    U[c] = std::min(1.0, std::max(0.0, a) + 0.25 * std::max(0.0, e) + 1e-12);
    K[c] = std::max(0.0, b) * (1.0 + 1e-9) + 0.25 * std::max(0.0, f);
  }
  // bounds(0, 16, U, K) and ramps(0, 16, U, K, Ua, Ka) from the folds of the rows over all intervals,
  // per axis c as CubicRecordKernels::cubic_node gives them (f[c]: mu, du, tmax, tmin, st, mk, dk, kmax,
  // kmin, sk).
  static void whole_from(const double (&f)[3][10], Vec3& U, Vec3& K, Vec3 (&Ua)[2], Vec3 (&Ka)[2]) noexcept {
    for (int c = 0; c < 3; ++c) bounds_from(c, f[c][0], f[c][5], f[c][1], f[c][6], U, K);
    for (int c = 0; c < 3; ++c) ramps_from(c, f[c][2], f[c][3], f[c][7], f[c][8], f[c][4], f[c][9], U, K, Ua, Ka);
  }
  // bounds(0, 16, U, K) and ramps(0, 16, U, K, Ua, Ka): the whole blend. With two-lane packs
  // (simd::Batch<2>) the folds over the intervals run two rows at a time (lane 0 one row, lane 1
  // another), each lane in the order of the intervals with std::max / std::min's result: std::max(acc, x)
  // is B::max(x, acc) and std::min(acc, x) is B::min(x, acc), ties and signed zeros included, so the
  // values are the loops' bit for bit.
  void whole(Vec3& U, Vec3& K, Vec3 (&Ua)[2], Vec3 (&Ka)[2]) const noexcept {
#if defined(__GNUC__)
    using B = simd::Batch<2>;
    // the left fold of rows a (lane 0) and b (lane 1) over the 16 intervals with op(acc, x)
    const auto fold = [](const double* a, const double* b, const auto& op) {
      B::D acc = op(B::D{a[0], b[0]}, B::D{a[1], b[1]});
      for (int r = 2; r < 16; ++r) acc = op(acc, B::D{a[r], b[r]});
      return acc;
    };
    const auto mx = [](B::D acc, B::D x) { return B::max(x, acc); };
    const auto mn = [](B::D acc, B::D x) { return B::min(x, acc); };
    for (int c = 0; c < 3; ++c) {
      const B::D ab = fold(mu[c], mk[c], mx), ef = fold(du[c], dk[c], mx);
      bounds_from(c, B::lane(ab, 0), B::lane(ab, 1), B::lane(ef, 0), B::lane(ef, 1), U, K);
    }
    for (int c = 0; c < 3; ++c) {
      const B::D x = fold(tmax[c], kmax[c], mx), n = fold(tmin[c], kmin[c], mn), ef = fold(st[c], sk[c], mx);
      ramps_from(c, B::lane(x, 0), B::lane(n, 0), B::lane(x, 1), B::lane(n, 1), B::lane(ef, 0), B::lane(ef, 1), U,
                 K, Ua, Ka);
    }
#else
    bounds(0, 16, U, K);
    ramps(0, 16, U, K, Ua, Ka);
#endif
  }
  // bounds(r, r + 1, U, K) and ramps(r, r + 1, U, K, Ua, Ka) once the single-interval terms are filled
  void single(int r, Vec3& U, Vec3& K, Vec3 (&Ua)[2], Vec3 (&Ka)[2]) const noexcept {
    for (int c = 0; c < 3; ++c) {
      U[c] = one_u[c][r];
      K[c] = one_k[c][r];
      Ua[0][c] = Ua[1][c] = one_ua[c][r];
      Ka[0][c] = one_ka[0][c][r];
      Ka[1][c] = one_ka[1][c][r];
    }
  }
};

}  // namespace netshape::motion::detail
