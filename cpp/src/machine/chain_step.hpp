#pragma once
// The chain step of the exact synthesis, written once over a pack of W points (simd::Batch<W>): W = 1
// is the one-point kernel behind `tip_error` (lanes.cpp), W = 2, 4, 8 the batch kernel behind
// `tip_error_lanes` (kernels/lanes.cpp, one copy per instruction set). Every lane runs the operations
// of the one-point kernel in the same order and none fuses a multiply-add, so a lane's results equal
// the one-point results bit for bit. Private; everything here has internal linkage, so the copies
// compiled for different instruction sets never share a symbol.
#include <cmath>

#include "axis_components.hpp"
#include "core/simd.hpp"
#include "netshape/core/error.hpp"
#include "netshape/machine/synthesis.hpp"
#include "rotation.hpp"

namespace netshape::machine {

namespace detail {
/// The one-point exact kernel (lanes.cpp): e(p) [mm], and the first-order Jacobian when `jacobian`
/// is not null; fills the scratch of `data` like `tip_error_and_jacobian`. Throws for a refused table.
Vec3 exact_point(MachineData& data, const Vec3& p, Mat3* jacobian);
}  // namespace detail

namespace {
template <int W>
using Pack = typename simd::Batch<W>::D;

template <class V>
NETSHAPE_SIMD_INLINE V splat(double x) {
  if constexpr (sizeof(V) == sizeof(double)) {
    return x;
  } else {
    V v;
    for (std::size_t w = 0; w < sizeof(V) / sizeof(double); ++w) v[w] = x;  // one broadcast
    return v;
  }
}
// (row[0][off], row[1][off], …) built in registers (no store-to-load round trip)
template <int W>
NETSHAPE_SIMD_INLINE Pack<W> gather_lanes(const double* const* row, int off) {
  if constexpr (W == 1) {
    return row[0][off];
  } else if constexpr (W == 2) {
    return Pack<W>{row[0][off], row[1][off]};
  } else if constexpr (W == 4) {
    return Pack<W>{row[0][off], row[1][off], row[2][off], row[3][off]};
  } else {
    return Pack<W>{row[0][off], row[1][off], row[2][off], row[3][off],
                                      row[4][off], row[5][off], row[6][off], row[7][off]};
  }
}
template <class V>
NETSHAPE_SIMD_INLINE V load_lanes(const double* x) {
  V v;
  __builtin_memcpy(&v, x, sizeof v);
  return v;
}
template <class V>
NETSHAPE_SIMD_INLINE void store_lanes(double* x, const V& v) {
  __builtin_memcpy(x, &v, sizeof v);
}
template <int W>
NETSHAPE_SIMD_INLINE double lane(const Pack<W>& v, int w) {
  if constexpr (W == 1)
    return v;
  else
    return v[w];
}

/// What a pack computes: the tip error; with the first-order Jacobian (`tip_error_and_jacobian`); or with
/// it also the exact Jacobian and the curvature terms left in MachineData (`tip_error_lanes` with
/// derivatives).
enum class Outputs : unsigned char { value, jacobian, all };
/// sin and cos − 1 of the angles: the short Taylor series, exact to rounding when every |angle| < 1e-3
/// (lanes with a larger angle are flagged for `redo`), or `sincos_m1` (any angle; one point only).
enum class Angles : unsigned char { taylor, exact };

struct PackFlags {
  unsigned bad = 0;   ///< lane w (bit w): a table refused its position or the point is not finite
  unsigned redo = 0;  ///< lane w: an angle ≥ 1e-3 rad, Angles::taylor does not hold there
};

// One pack of W points, lanes [first, first + W) of the batch arrays. Axis by axis along the chain: its
// six components, sin/cos − 1 of its angles, its 3×3 step (few values live at a time). `Batch`: a refused
// table position flags the lane in `bad` (else: throws the table's message, one point).
template <int W, Outputs O, Angles A, bool Batch>
NETSHAPE_SIMD_INLINE PackFlags chain_pack(const CompiledMachine& cm, MachineData& data,
                                          const double (&pin)[3][batch_lanes], int first,
                                          double (&out)[3][batch_lanes], double (*jac)[9][batch_lanes]) {
  static_assert(A == Angles::taylor || W == 1, "sincos_m1 is scalar");
  using V = Pack<W>;
  constexpr bool Jacobian = O != Outputs::value;
  constexpr bool Exact = O == Outputs::all;  // exact Jacobian and curvature
  PackFlags flags;
  V P[3];
  for (int c = 0; c < 3; ++c) P[c] = load_lanes<V>(&pin[c][first]);
  if constexpr (Batch) {
    const V z = (P[0] - P[0]) + (P[1] - P[1]) + (P[2] - P[2]);  // 0 where the point is finite, else NaN
    for (int w = 0; w < W; ++w)
      if (!(lane<W>(z, w) == 0.0)) flags.bad |= 1u << w;
  }
  // How each axis' components are evaluated: a polynomial axis by a six-component Horner on its packed
  // coefficients, a uniform table with every lane inside it by vector interpolation, anything else per
  // lane (other tables, lanes outside a table, mixed axes) into ev/sv (lane 3k + c: rotation c of axis k;
  // lane 9 + 3k + c: translation c of axis k).
  enum : unsigned char { axis_poly, axis_table, per_lane };
  unsigned char how[3];
  for (int k = 0; k < 3; ++k) {
    const detail::AxisKernel& ker = cm.kernels[k];
    if (ker.mode == detail::AxisKernel::Mode::polynomial) {
      how[k] = axis_poly;
    } else if (ker.mode == detail::AxisKernel::Mode::table && ker.grid.uniform) {
      bool inside = true;
      for (int w = 0; w < W; ++w) {
        const double q = pin[k][first + w];
        inside = inside && q >= ker.grid.lo && q <= ker.grid.hi;
      }
      how[k] = inside ? axis_table : per_lane;
    } else {
      how[k] = per_lane;
    }
  }
  double ev[18][W], sv[18][W];
  for (int k = 0; k < 3; ++k) {
    if (how[k] != per_lane) continue;
    for (int w = 0; w < W; ++w) {
      const double q = pin[k][first + w];
      double v[6], d[6];
      const bool finite = !Batch || std::isfinite(q);
      const ErrorFunction* refused = nullptr;
      if (finite) {
        if constexpr (Batch)
          refused = detail::axis_components_outlined<Jacobian>(cm, k, q, v, d);
        else
          refused = detail::axis_components<Jacobian>(cm, k, q, v, d);
      }
      if (refused && !Batch) detail::throw_refused(*refused, q);
      if (refused || !finite) {
        for (int c = 0; c < 6; ++c) v[c] = d[c] = 0.0;
        flags.bad |= 1u << w;
      }
      for (int c = 0; c < 3; ++c) {
        ev[9 + 3 * k + c][w] = v[c];
        ev[3 * k + c][w] = v[3 + c];
        if (Jacobian) {
          sv[9 + 3 * k + c][w] = d[c];
          sv[3 * k + c][w] = d[3 + c];
        }
      }
    }
  }
  V v0 = splat<V>(cm.tip_nominal[0]), v1 = splat<V>(cm.tip_nominal[1]), v2 = splat<V>(cm.tip_nominal[2]);
  V d0 = splat<V>(cm.tip_local[0]), d1 = splat<V>(cm.tip_local[1]), d2 = splat<V>(cm.tip_local[2]);
  V arm[3][3], eps[3][3], eps_slope[3][3], delta_slope[3][3];
  V curv[3][6];  // second derivatives of the components of a polynomial axis (0 otherwise), as e[]
  // exact Jacobian by forward differentiation along the chain: D[r][m] = ∂d_r/∂q_m
  V D[3][3];
  if (Exact)
    for (int r = 0; r < 3; ++r)
      for (int m = 0; m < 3; ++m) D[r][m] = splat<V>(0.0);
  bool added[3] = {false, false, false};  // axis m's q_m e_m is in the nominal position v
  const V one = splat<V>(1.0);
  V big = splat<V>(0.0);  // largest squared angle of each lane
  for (int i = 0; i < 3; ++i) {
    const detail::ChainStep& st = cm.steps[i];
    const int k = st.axis;
    const V q = P[k];
    // e[0..2]: angles (EAk, EBk, ECk) [rad], e[3..5]: translations (EXk, EYk, EZk) [mm]
    V e[6], sl[6], s2[6];
    const int lane_of[6] = {3 * k, 3 * k + 1, 3 * k + 2, 9 + 3 * k, 10 + 3 * k, 11 + 3 * k};
    if (how[k] == axis_poly) {
      // Horner on the packed coefficients [j * 6 + c] (translations c = 0..2, rotations 3..5), the
      // first and second derivatives by the same recurrence
      const detail::AxisKernel& ker = cm.kernels[k];
      const double* ck = ker.packed.data();
      const int lk = ker.terms - 1;
      constexpr int comp[6] = {3, 4, 5, 0, 1, 2};
#pragma GCC unroll 6
      for (int c = 0; c < 6; ++c) {
        e[c] = splat<V>(ck[lk * 6 + comp[c]]);
        if (Jacobian) sl[c] = s2[c] = splat<V>(0.0);
      }
      for (int j = lk - 1; j >= 0; --j) {
        const double* cj = ck + j * 6;
#pragma GCC unroll 6
        for (int c = 0; c < 6; ++c) {
          if (Exact) s2[c] = s2[c] * q + sl[c];
          if (Jacobian) sl[c] = sl[c] * q + e[c];
          e[c] = e[c] * q + cj[comp[c]];
        }
      }
      if (Exact)
        for (int c = 0; c < 6; ++c) curv[k][c] = s2[c] + s2[c];
    } else if (how[k] == axis_table) {
      // a uniform table, every lane inside it: one row lookup per lane, then table_interpolation's
      // formulas on whole packs
      const detail::AxisKernel& ker = cm.kernels[k];
      const V u = detail::uniform_position(q, ker.grid.lo, ker.grid.inv_step);
      V fi;
      const double* row[W];
      if constexpr (W == 1) {
        const int i = detail::uniform_segment(u, ker.terms);
        fi = i;
        row[0] = ker.packed.data() + static_cast<std::ptrdiff_t>(i) * 6;
      } else {
        // detail::uniform_segment on every lane: truncation as static_cast<int>, then min(i, n − 2)
        using I = typename simd::Batch<W>::I;
        I iv = __builtin_convertvector(u, I);
        const I top = iv - iv + (ker.terms - 2);
        iv = iv > top ? top : iv;
        fi = __builtin_convertvector(iv, V);
        for (int w = 0; w < W; ++w) row[w] = ker.packed.data() + static_cast<std::ptrdiff_t>(iv[w]) * 6;
      }
      const V t = u - fi, inv_step = splat<V>(ker.grid.inv_step);
      const int comp[6] = {3, 4, 5, 0, 1, 2};
#pragma GCC unroll 6
      for (int c = 0; c < 6; ++c) {
        const V a = gather_lanes<W>(row, comp[c]), b = gather_lanes<W>(row, 6 + comp[c]);
        e[c] = detail::interpolate(a, b, t);
        if (Jacobian) sl[c] = detail::segment_slope(a, b, inv_step);
      }
      if (Exact)
        for (int c = 0; c < 6; ++c) curv[k][c] = splat<V>(0.0);
    } else {
#pragma GCC unroll 6
      for (int c = 0; c < 6; ++c) {
        e[c] = load_lanes<V>(ev[lane_of[c]]);
        if (Jacobian) sl[c] = load_lanes<V>(sv[lane_of[c]]);
      }
      if (Exact)
        for (int c = 0; c < 6; ++c) curv[k][c] = splat<V>(0.0);
    }
    if (Jacobian) {
      for (int c = 0; c < 3; ++c) {
        eps[k][c] = e[c];
        eps_slope[k][c] = sl[c];
        delta_slope[k][c] = sl[3 + c];
      }
      if constexpr (!Batch) {
        // one point: the components at p are scratch outputs of tip_error_and_jacobian
        data.delta[k] = Vec3(e[3], e[4], e[5]);
        data.epsilon[k] = Vec3(e[0], e[1], e[2]);
        data.delta_slope[k] = Vec3(sl[3], sl[4], sl[5]);
        data.epsilon_slope[k] = Vec3(sl[0], sl[1], sl[2]);
      }
    }
    // sin and cos − 1 of the three angles
    V sn[3], cm1[3];
    if constexpr (A == Angles::taylor) {
      constexpr double k6 = -1.0 / 6.0, k120 = 1.0 / 120.0, k24 = 1.0 / 24.0, k720 = -1.0 / 720.0;
#pragma GCC unroll 3
      for (int c = 0; c < 3; ++c) {
        const V x2 = e[c] * e[c];
        big = big > x2 ? big : x2;
        sn[c] = e[c] + e[c] * x2 * (k6 + x2 * k120);
        cm1[c] = x2 * (-0.5 + x2 * (k24 + x2 * k720));
      }
    } else {
      for (int c = 0; c < 3; ++c) detail::sincos_m1(e[c], sn[c], cm1[c]);
    }
    // R − I from sin and cos − 1 of (a, b, c), R = Rz(c)·Ry(b)·Rx(a) (no cancellation)
    const V sa = sn[0], sb = sn[1], sc = sn[2];
    const V cma = cm1[0], cmb = cm1[1], cmc = cm1[2];
    const V ca = one + cma, cb = one + cmb, cc = one + cmc;
    const V sasb = sa * sb, casb = ca * sb;
    const V m00 = cmb + cmc + cmb * cmc, m01 = sasb * cc - ca * sc, m02 = casb * cc + sa * sc;
    const V m10 = cb * sc, m11 = sasb * sc + cma + cmc + cma * cmc, m12 = casb * sc - sa * cc;
    const V m20 = -sb, m21 = sa * cb, m22 = cma + cmb + cma * cmb;
    // t − q u = q (u' − u) + δ
    const Vec3& du = cm.direction[k];
    const V t0 = q * du[0] + e[3], t1 = q * du[1] + e[4], t2 = q * du[2] + e[5];
    V c0, c1, c2;
    if (st.tool) {
      // v_frame = o + R (v + d) + q u' + δ ; nominal o + v + q u. The part that does not depend on d is
      // formed first, so that the chain of dependent operations is one 3×3 product per axis.
      if (Jacobian) arm[k][0] = v0, arm[k][1] = v1, arm[k][2] = v2;
      c0 = m00 * v0 + m01 * v1 + m02 * v2 + t0;
      c1 = m10 * v0 + m11 * v1 + m12 * v2 + t1;
      c2 = m20 * v0 + m21 * v1 + m22 * v2 + t2;
      // v += origin + q u
      const V o0 = k == 0 ? st.origin[0] + q : splat<V>(st.origin[0]);
      const V o1 = k == 1 ? st.origin[1] + q : splat<V>(st.origin[1]);
      const V o2 = k == 2 ? st.origin[2] + q : splat<V>(st.origin[2]);
      v0 += o0, v1 += o1, v2 += o2;
    } else {
      // The table moves by −t = −(q u' + δ) and turns by R⁻¹ about its own origin:
      // W = R (v + d − o + t) ; nominal v − o + q u (arm: the point relative to the carriage's current origin).
      v0 -= st.origin[0], v1 -= st.origin[1], v2 -= st.origin[2];
      if (k == 0) v0 += q;
      if (k == 1) v1 += q;
      if (k == 2) v2 += q;
      if (Jacobian) arm[k][0] = v0, arm[k][1] = v1, arm[k][2] = v2;
      const V w0 = v0 + t0, w1 = v1 + t1, w2 = v2 + t2;
      c0 = t0 + (m00 * w0 + m01 * w1 + m02 * w2);
      c1 = t1 + (m10 * w0 + m11 * w1 + m12 * w2);
      c2 = t2 + (m20 * w0 + m21 * w1 + m22 * w2);
    }
    const V n0 = d0 + (m00 * d0 + m01 * d1 + m02 * d2 + c0);
    const V n1 = d1 + (m10 * d0 + m11 * d1 + m12 * d2 + c1);
    const V n2 = d2 + (m20 * d0 + m21 * d1 + m22 * d2 + c2);
    if (Exact) {
      // tool: n = R d + M v + t (v before its update); table: n = R d + t + M (v + t) (v after it).
      // ∂n/∂q_m = R ∂d/∂q_m + M ∂v/∂q_m, and for m = k also t' (table: R t') + R' x with
      // x = d + v (tool) or d + v + t (table); R' x = ω × R x, ω = c' ẑ + b' Rz ŷ + a' Rz Ry x̂, and
      // R x = v + n − t (tool) or v + n (table).
      if (!st.tool) added[k] = true;
      const V M[3][3] = {{m00, m01, m02}, {m10, m11, m12}, {m20, m21, m22}};
      V Dn[3][3];
      for (int r = 0; r < 3; ++r)
        for (int m = 0; m < 3; ++m) {
          V a = D[r][m] + (M[r][0] * D[0][m] + M[r][1] * D[1][m] + M[r][2] * D[2][m]);
          if (added[m]) a += M[r][m];
          Dn[r][m] = a;
        }
      const V tp0 = du[0] + sl[3], tp1 = du[1] + sl[4], tp2 = du[2] + sl[5];
      V x0 = arm[k][0] + n0, x1 = arm[k][1] + n1, x2 = arm[k][2] + n2;
      V g0 = tp0, g1 = tp1, g2 = tp2;
      if (st.tool) {
        x0 -= t0, x1 -= t1, x2 -= t2;
      } else {
        g0 += m00 * tp0 + m01 * tp1 + m02 * tp2;
        g1 += m10 * tp0 + m11 * tp1 + m12 * tp2;
        g2 += m20 * tp0 + m21 * tp1 + m22 * tp2;
      }
      const V w0 = sl[0] * cb * cc - sl[1] * sc, w1 = sl[0] * cb * sc + sl[1] * cc, w2 = sl[2] - sl[0] * sb;
      Dn[0][k] += g0 + (w1 * x2 - w2 * x1);
      Dn[1][k] += g1 + (w2 * x0 - w0 * x2);
      Dn[2][k] += g2 + (w0 * x1 - w1 * x0);
      for (int r = 0; r < 3; ++r)
        for (int m = 0; m < 3; ++m) D[r][m] = Dn[r][m];
      if (st.tool) added[k] = true;
    }
    d0 = n0, d1 = n1, d2 = n2;
  }
  if (Exact)
    for (int m = 0; m < 3; ++m)
      for (int r = 0; r < 3; ++r) store_lanes(&data.lane_jacobian[3 * m + r][first], D[r][m]);
  store_lanes(&out[0][first], d0);
  store_lanes(&out[1][first], d1);
  store_lanes(&out[2][first], d2);
  if constexpr (A == Angles::taylor)
    for (int w = 0; w < W; ++w)
      if (!(lane<W>(big, w) < 1e-6)) flags.redo |= 1u << w;
  if (Jacobian) {
    // first-order Jacobian, column k = δ'_k + (u'_k − u_k)₁ + ε'_k × r_k + (Σ_{j: arm grows with q_k} ε_j) × u_k
    for (int k = 0; k < 3; ++k) {
      V es0 = splat<V>(0.0), es1 = es0, es2 = es0;
      for (int j = 0; j < 3; ++j)
        if (cm.arm_grows[k][j]) es0 += eps[j][0], es1 += eps[j][1], es2 += eps[j][2];
      const V a0 = eps_slope[k][0], a1 = eps_slope[k][1], a2 = eps_slope[k][2];
      const V r0 = arm[k][0], r1 = arm[k][1], r2 = arm[k][2];
      const V col[3] = {a1 * r2 - a2 * r1, a2 * r0 - a0 * r2, a0 * r1 - a1 * r0};
      // (es × u_k): x̂ → (0, es2, −es1); ŷ → (−es2, 0, es0); ẑ → (es1, −es0, 0)
      const V zero = splat<V>(0.0);
      const V x[3] = {k == 0 ? zero : (k == 1 ? -es2 : es1), k == 0 ? es2 : (k == 1 ? zero : -es0),
                      k == 0 ? -es1 : (k == 1 ? es0 : zero)};
      for (int r = 0; r < 3; ++r) {
        const V c = delta_slope[k][r] + cm.direction_linear[k][r] + col[r] + x[r];
        store_lanes(&(*jac)[3 * k + r][first], c);
      }
      if (Exact) {
        // second-order terms: g_k = δ''_k + ε''_k × r_k, and ε'_k
        const V b0 = curv[k][0], b1 = curv[k][1], b2 = curv[k][2];
        const V g[3] = {curv[k][3] + (b1 * r2 - b2 * r1), curv[k][4] + (b2 * r0 - b0 * r2),
                        curv[k][5] + (b0 * r1 - b1 * r0)};
        for (int r = 0; r < 3; ++r) {
          store_lanes(&data.lane_curvature[3 * k + r][first], g[r]);
          store_lanes(&data.lane_curvature[9 + 3 * k + r][first], eps_slope[k][r]);
        }
      }
    }
  }
  if constexpr (Batch && A == Angles::taylor) {
    // lanes with an angle ≥ 1e-3 rad (not a realistic geometric error, but allowed): the one-point kernel
    // (their exact Jacobian and curvature stay those of the Taylor series)
    const unsigned redo = flags.redo & ~flags.bad;
    if (redo) {
      for (int w = 0; w < W; ++w) {
        if (!((redo >> w) & 1u)) continue;
        const Vec3 pw(pin[0][first + w], pin[1][first + w], pin[2][first + w]);
        Mat3 jw;
        const Vec3 ew = detail::exact_point(data, pw, Jacobian ? &jw : nullptr);
        if (Jacobian)
          for (int col = 0; col < 3; ++col)
            for (int r = 0; r < 3; ++r) (*jac)[3 * col + r][first + w] = jw(r, col);
        for (int c = 0; c < 3; ++c) out[c][first + w] = ew[c];
      }
    }
  }
  return flags;
}

// The batch of `batch_lanes` points in packs of W.
template <int W>
NETSHAPE_SIMD_INLINE unsigned lanes_impl(MachineData& data, const double (&p)[3][batch_lanes],
                                         double (&e)[3][batch_lanes], double (*jac)[9][batch_lanes]) {
  const CompiledMachine& cm = data.compiled();
  unsigned bad = 0;
  if (jac) {
    for (int f = 0; f < batch_lanes; f += W)
      bad |= chain_pack<W, Outputs::all, Angles::taylor, true>(cm, data, p, f, e, jac).bad << f;
  } else {
    for (int f = 0; f < batch_lanes; f += W)
      bad |= chain_pack<W, Outputs::value, Angles::taylor, true>(cm, data, p, f, e, nullptr).bad << f;
  }
  return bad;
}

}  // namespace
}  // namespace netshape::machine
