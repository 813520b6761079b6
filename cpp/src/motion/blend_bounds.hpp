#pragma once
/// \file blend_bounds.hpp
/// Internal: per-axis bounds of a cubic Bézier's unit tangent and curvature vector over runs of its
/// arc-length table intervals, unsigned (the speed caps) and signed (the acceleration terms of each
/// direction of a speed change); the planner's corner blends (planner_blend.cpp) and cubic blocks
/// (planner_cubic.cpp) bound each of their pieces with them.

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <limits>

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
  // sides (U, K): speeding up (tx, kx), (−tn, −kn); slowing down (−tn, kx), (tx, −kn)
  const double side[2][2][2] = {{{tx, kx}, {-tn, -kn}}, {{-tn, kx}, {tx, -kn}}};
  for (int d = 0; d < 2; ++d) {
    double u = 0, k = -std::numeric_limits<double>::infinity();
    for (int q = 0; q < 2; ++q)
      if (side[d][q][0] > 0) {
        u = std::max(u, side[d][q][0]);
        k = std::max(k, side[d][q][1]);
      }
    if (!(u > 0)) k = 0;
    U[d] = std::min(u, Uabs);
    K[d] = std::min(k, Kabs);
  }
}

// Per-axis bounds of a blend's unit tangent |u_i| (U) and curvature vector |κ n_i| (K) over runs of
// its 17 table nodes, with a margin for what lies between the nodes (a quarter of the largest second
// difference of the node values, twice the parabolic estimate). The raw maxima are taken once per
// table interval; a run's bound is the max over its intervals (max is exact, so the bounds of the
// whole blend equal those computed over all nodes at once).
//
// Signed: per table interval the largest and smallest u_i and κn_i at its two nodes, widened by the
// same kind of margin from the second differences of the signed values. ramps() turns them into the
// per-axis terms of the axis box for each direction of a speed change (see there).
struct BlendBounds {
  double mu[16][3], mk[16][3], du[16][3], dk[16][3];  // raw maxima per table interval
  double tmax[16][3], tmin[16][3], kmax[16][3], kmin[16][3];  // signed extremes per interval
  double st[16][3], sk[16][3];  // largest second difference of the signed values per interval
  void fill(const std::array<Vec3, 17>& T, const std::array<Vec3, 17>& Kv) noexcept {
    double t[17][3], k[17][3], dt[17][3], dkk[17][3], ds[17][3], dks[17][3];
    for (int i = 0; i < 17; ++i)
      for (int c = 0; c < 3; ++c) {
        t[i][c] = std::abs(T[static_cast<std::size_t>(i)][c]);
        k[i][c] = std::abs(Kv[static_cast<std::size_t>(i)][c]);
      }
    for (int c = 0; c < 3; ++c)  // ends: none
      dt[0][c] = dkk[0][c] = dt[16][c] = dkk[16][c] = ds[0][c] = dks[0][c] = ds[16][c] = dks[16][c] = 0.0;
    for (int i = 1; i <= 15; ++i)
      for (int c = 0; c < 3; ++c) {
        const auto im = static_cast<std::size_t>(i - 1), ii = static_cast<std::size_t>(i),
                   ip = static_cast<std::size_t>(i + 1);
        dt[i][c] = std::abs(t[i - 1][c] - 2 * t[i][c] + t[i + 1][c]);
        dkk[i][c] = std::abs(k[i - 1][c] - 2 * k[i][c] + k[i + 1][c]);
        ds[i][c] = std::abs(T[im][c] - 2 * T[ii][c] + T[ip][c]);
        dks[i][c] = std::abs(Kv[im][c] - 2 * Kv[ii][c] + Kv[ip][c]);
      }
    for (int r = 0; r < 16; ++r)
      for (int c = 0; c < 3; ++c) {
        const auto r0 = static_cast<std::size_t>(r), r1 = static_cast<std::size_t>(r + 1);
        mu[r][c] = std::max(t[r][c], t[r + 1][c]);
        mk[r][c] = std::max(k[r][c], k[r + 1][c]);
        du[r][c] = std::max(dt[r][c], dt[r + 1][c]);
        dk[r][c] = std::max(dkk[r][c], dkk[r + 1][c]);
        tmax[r][c] = std::max(T[r0][c], T[r1][c]);
        tmin[r][c] = std::min(T[r0][c], T[r1][c]);
        kmax[r][c] = std::max(Kv[r0][c], Kv[r1][c]);
        kmin[r][c] = std::min(Kv[r0][c], Kv[r1][c]);
        st[r][c] = std::max(ds[r][c], ds[r + 1][c]);
        sk[r][c] = std::max(dks[r][c], dks[r + 1][c]);
      }
  }
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
      double tx = tmax[r0][c], tn = tmin[r0][c], kx = kmax[r0][c], kn = kmin[r0][c], e = st[r0][c],
             f = sk[r0][c];
      for (int r = r0 + 1; r < r1; ++r) {
        tx = std::max(tx, tmax[r][c]);
        tn = std::min(tn, tmin[r][c]);
        kx = std::max(kx, kmax[r][c]);
        kn = std::min(kn, kmin[r][c]);
        e = std::max(e, st[r][c]);
        f = std::max(f, sk[r][c]);
      }
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
  }
  // bounds over the table intervals [r0, r1)
  void bounds(int r0, int r1, Vec3& U, Vec3& K) const noexcept {
    for (int c = 0; c < 3; ++c) {
      double a = mu[r0][c], b = mk[r0][c], e = du[r0][c], f = dk[r0][c];
      for (int r = r0 + 1; r < r1; ++r) {
        a = std::max(a, mu[r][c]);
        b = std::max(b, mk[r][c]);
        e = std::max(e, du[r][c]);
        f = std::max(f, dk[r][c]);
      }
      U[c] = std::min(1.0, std::max(0.0, a) + 0.25 * std::max(0.0, e) + 1e-12);
      K[c] = std::max(0.0, b) * (1.0 + 1e-9) + 0.25 * std::max(0.0, f);
    }
  }
};

}  // namespace netshape::motion::detail
