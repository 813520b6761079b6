// The planner's cubic-record kernels (kernels/cubic_record_kernels.hpp): the array work over the pieces of a cubic
// block, one lane per piece, as wide as the instruction set being compiled (simd::native_width),
// compiled once per instruction set by netshape_add_kernels. Only the record and plain doubles cross
// between the kernels and the rest of the library, and the entry points are flattened, so nothing is
// left out of line for the linker to share with baseline code.
//
// The operations are the scalar ones element by element: std::max(a, b) is B::max(b, a) and
// std::min(a, b) is B::min(b, a) (B::max(a, b) is a > b ? a : b), including ties and signed zeros.
#include "core/simd.hpp"  // first: it wraps the intrinsic headers (see there)

#include <algorithm>
#include <cmath>
#include <limits>

#include "motion/planner/blend_bounds.hpp"
#include "motion/kernels/cubic_record_kernels.hpp"

namespace netshape::motion::detail::NETSHAPE_KERNEL_ISA {
namespace {

using B = simd::Batch<simd::native_width>;
using D = B::D;
using M = B::M;
constexpr int W = simd::native_width;
static_assert(CubicRecord::pieces % W == 0, "whole packets over the record's arrays");

// One step of min_ratio()'s loop (planner/state.hpp): the fraction num/den replaces the best nb/db
// where den > 0 and either none was taken yet (has false) or num·db < nb·den.
NETSHAPE_SIMD_INLINE void ratio_step(D num, D den, D& nb, D& db, M& has) {
  const M better = B::lt(B::mul(num, db), B::mul(nb, den));
  const M take = B::land(B::gt(den, B::set(0.0)), B::lor(better, B::lnot(has)));
  nb = B::blend(take, nb, num);
  db = B::blend(take, db, den);
  has = B::lor(has, take);
}

// PlannerState::axis_box_profile() without windows (a piece's length is ≥ 0: the ramps get all of it),
// then detail::make_trapezoid() with the cruise cap sqrt(wp); min_ratio()'s branches as masks, its fast
// path being its loop's result when every denominator is > 0.
__attribute__((flatten)) void freeze(CubicRecord& r, const double* A, double amin) {
  const D zero = B::set(0.0), two = B::set(2.0), half = B::set(0.5), one = B::set(1.0), inf = B::set(std::numeric_limits<double>::infinity());
  const D floor_a = B::set(1e-6 * amin), amin_ = B::set(amin);
  const D Ai[3] = {B::set(A[0]), B::set(A[1]), B::set(A[2])};
  for (int k = 0; k < r.np; k += W) {
    const auto at = [k](const double* row) NETSHAPE_SIMD_LAMBDA { return B::loadu(row + k); };
    const D vs = at(r.vs), ve = at(r.ve), len = at(r.len);
    const D vs2 = B::mul(vs, vs), ve2 = B::mul(ve, ve);
    const D S = B::add(vs2, ve2), wlow = B::min(ve2, vs2);
    const D lr2 = B::mul(two, len);
    // the peak squared speed: min(v_max², the two directions' min_ratio of (U·S + 2L·Ae)/(2U + 2L·Ke)),
    // Ke = max(K, 0), Ae = A − min(K, 0)·wlow
    const D vmax = at(r.v_max);
    D wp = B::mul(vmax, vmax);
    for (int d = 0; d < 2; ++d) {
      D nb = zero, db = one;
      M has = B::lt(one, zero);  // none
      for (int i = 0; i < 3; ++i) {
        const D kk = at(r.ramp_k[d][i]), U = at(r.ramp_u[d][i]);
        const D Ae = B::sub(Ai[i], B::mul(B::min(zero, kk), wlow));
        ratio_step(B::add(B::mul(U, S), B::mul(lr2, Ae)), B::add(B::mul(two, U), B::mul(lr2, B::max(zero, kk))), nb,
                   db, has);
      }
      wp = B::min(B::blend(has, inf, B::div(nb, db)), wp);
    }
    wp = B::max(B::max(ve2, vs2), wp);
    // the tangential acceleration: the smaller of the two directions' min_ratio of (Ae − Ke·wp)/U
    D a = inf;
    for (int d = 0; d < 2; ++d) {
      D nb = zero, db = one;
      M has = B::lt(one, zero);
      for (int i = 0; i < 3; ++i) {
        const D kk = at(r.ramp_k[d][i]), U = at(r.ramp_u[d][i]);
        const D Ae = B::sub(Ai[i], B::mul(B::min(zero, kk), wlow));
        ratio_step(B::sub(Ae, B::mul(B::max(zero, kk), wp)), U, nb, db, has);
      }
      const D ad = B::blend(has, inf, B::div(nb, db));
      a = d == 0 ? ad : B::min(ad, a);
    }
    a = B::blend(B::gt(a, floor_a), floor_a, a);  // (a NaN becomes the floor: a is a number below)
    a = B::blend(B::ge(a, inf), a, amin_);
    // make_trapezoid() without windows
    const D vlow = B::max(ve, vs);
    D vp = B::sqrt(B::max(B::div(B::add(B::mul(B::mul(two, a), len), S), two), zero));
    vp = B::max(B::min(B::max(vlow, B::sqrt(wp)), vp), vlow);
    const D need = B::sub(B::mul(B::mul(two, vp), vp), S);
    const M raise = B::land(B::gt(len, zero), B::gt(need, B::mul(lr2, a)));
    a = B::blend(raise, a, B::div(need, lr2));
    const D ia = B::div(one, a);
    const D t1 = B::mul(B::sub(vp, vs), ia), d1 = B::mul(B::mul(half, B::add(vs, vp)), t1);
    const D t3 = B::mul(B::sub(vp, ve), ia), d3 = B::mul(B::mul(half, B::add(vp, ve)), t3);
    D d2 = B::max(B::sub(B::sub(len, d1), d3), zero);
    const M moving = B::gt(vp, zero);
    D d2m = B::add(d2, B::sub(len, B::add(B::add(d1, d2), d3)));
    d2m = B::blend(B::lt(d2m, zero), d2m, zero);
    d2 = B::blend(moving, d2, d2m);
    const D t2 = B::blend(moving, zero, B::div(d2, vp));
    B::storeu(r.vp + k, vp);
    B::storeu(r.acc + k, a);
    B::storeu(r.t1 + k, t1);
    B::storeu(r.t2 + k, t2);
    B::storeu(r.t3 + k, t3);
    B::storeu(r.d1 + k, d1);
    B::storeu(r.d2 + k, d2);
    B::storeu(r.d3 + k, d3);
    B::storeu(r.dur + k, B::add(B::add(t1, t2), t3));
  }
}

// set_limits() of an axis-box piece and box_reach_both() (planner/push.cpp): den = U + 2L·max(K, 0),
// an = U − 2L·min(K, 0) per direction and axis, the three reciprocals from one division.
__attribute__((flatten)) unsigned caps_reach(CubicRecord& r, double feed_cap, const double* V, const double* A) {
  const D zero = B::set(0.0), one = B::set(1.0), two = B::set(2.0), inf = B::set(std::numeric_limits<double>::infinity());
  unsigned bad = 0;
  for (int k = 0; k < r.np; k += W) {
    const auto at = [k](const double* row) NETSHAPE_SIMD_LAMBDA { return B::loadu(row + k); };
    D v = B::set(feed_cap), wk = inf;
    for (int i = 0; i < 3; ++i) {
      const D U = at(r.u_abs[i]), K = at(r.k_abs[i]);
      v = B::blend(B::gt(U, zero), v, B::min(B::div(B::set(V[i]), U), v));
      wk = B::blend(B::gt(K, zero), wk, B::min(B::div(B::set(A[i]), K), wk));
    }
    v = B::blend(B::lt(wk, inf), v, B::min(B::sqrt(wk), v));
    B::storeu(r.v_max + k, v);
    const D L2 = B::mul(two, B::max(at(r.len), zero));
    M ok = B::lt(zero, one);  // all
    for (int d = 0; d < 2; ++d) {
      D den[3], an[3];
      for (int i = 0; i < 3; ++i) {
        const D u = at(r.ramp_u[d][i]), kk = at(r.ramp_k[d][i]);
        den[i] = B::add(u, B::mul(L2, B::max(zero, kk)));
        an[i] = B::sub(u, B::mul(L2, B::min(zero, kk)));
        ok = B::land(ok, B::gt(den[i], zero));
      }
      const D d01 = B::mul(den[0], den[1]), rr = B::div(one, B::mul(d01, den[2]));
      const D rd[3] = {B::mul(B::mul(den[1], den[2]), rr), B::mul(B::mul(den[0], den[2]), rr), B::mul(d01, rr)};
      double(&al)[3][CubicRecord::pieces] = d == 0 ? r.alpha : r.alpha_down;
      double(&be)[3][CubicRecord::pieces] = d == 0 ? r.beta : r.beta_down;
      for (int i = 0; i < 3; ++i) {
        B::storeu(al[i] + k, B::mul(an[i], rd[i]));
        B::storeu(be[i] + k, B::mul(B::mul(L2, B::set(A[i])), rd[i]));
      }
    }
    if (B::count(ok) < W) {
      alignas(64) double flag[W];
      B::storeu(flag, B::blend(ok, zero, one));  // 1 where ok
      for (int j = 0; j < W && k + j < r.np; ++j)
        if (flag[j] == 0.0) bad |= 1u << (k + j);
    }
  }
  return bad;
}

// The junction limits (the block's corner before the first piece, the cap of the piece before at the
// others: w = min(v_before, v_max)², std::min's operand order) and the live axes of the backward step
// (CubicRecord::set_live_axes(): the axes i where alpha_down < 0 or beta_down < w_junction on some piece).
__attribute__((flatten)) void junctions(CubicRecord& r, double v_corner) {
  alignas(64) double before[CubicRecord::pieces + W];
  before[0] = v_corner;
  for (int k = 0; k + 1 < r.np; ++k) before[k + 1] = r.v_max[k];
  const D zero = B::set(0.0);
  M binds[3] = {B::lt(zero, zero), B::lt(zero, zero), B::lt(zero, zero)};
  for (int k = 0; k < r.np; k += W) {
    const M v = B::valid(r.np - k);
    const D vj = B::min(B::loadu(r.v_max + k), B::loadu(before + k));
    const D wj = B::mul(vj, vj);
    B::storeu(r.w_junction + k, wj);
    for (int i = 0; i < 3; ++i) {
      const M holds = B::land(B::ge(B::loadu(r.alpha_down[i] + k), zero), B::ge(B::loadu(r.beta_down[i] + k), wj));
      binds[i] = B::lor(binds[i], B::land(v, B::lnot(holds)));
    }
  }
  r.live_down = 0;
  for (int i = 0; i < 3; ++i)
    if (B::any(binds[i])) r.live_down_axis[r.live_down++] = i;
}

// BlendBounds::bounds() and ramps() of single table intervals of axis c, the lanes' intervals from r
// (lanes outside v read as 0; full: all lanes valid): U, K, the one Ua of both directions, Ka of each
// (ramp_terms()' four cases as masks; negation flips the sign bit).
struct SingleTerms {
  D U, K, ua, ka0, ka1;
};
NETSHAPE_SIMD_INLINE SingleTerms single_terms(const BlendBounds& t, int c, int r, M v, bool full) {
  const D zero = B::set(0.0), one = B::set(1.0), minus_one = B::set(-1.0), quarter = B::set(0.25),
          eps = B::set(1e-12), grow = B::set(1.0 + 1e-9), shrink = B::set(1.0 - 1e-9);
  const auto at = [r, v, full](const double* row) NETSHAPE_SIMD_LAMBDA { return B::load(row + r, v, full); };
  SingleTerms s;
  // bounds(r, r + 1)
  s.U = B::min(B::add(B::add(B::max(at(t.mu[c]), zero), B::mul(quarter, B::max(at(t.du[c]), zero))), eps), one);
  s.K = B::add(B::mul(B::max(at(t.mk[c]), zero), grow), B::mul(quarter, B::max(at(t.dk[c]), zero)));
  // ramps(r, r + 1): the signed ranges with their margins, then ramp_terms()
  const D e = at(t.st[c]), f = at(t.sk[c]), kx0 = at(t.kmax[c]), kn0 = at(t.kmin[c]);
  const D tx = B::min(B::add(B::add(at(t.tmax[c]), B::mul(quarter, e)), eps), one);
  const D tn = B::max(B::sub(B::sub(at(t.tmin[c]), B::mul(quarter, e)), eps), minus_one);
  const D kx = B::add(B::mul(kx0, B::blend(B::gt(kx0, zero), shrink, grow)), B::mul(quarter, f));
  const D kn = B::sub(B::mul(kn0, B::blend(B::lt(kn0, zero), shrink, grow)), B::mul(quarter, f));
  const D mtn = -tn, mkn = -kn;
  const M up = B::gt(tx, zero), down = B::gt(mtn, zero);
  const D u = B::blend(up, B::blend(down, zero, mtn), B::blend(down, tx, B::max(mtn, tx)));
  const D kb = B::max(mkn, kx);
  const D k0 = B::blend(up, B::blend(down, zero, mkn), B::blend(down, kx, kb));
  const D k1 = B::blend(up, B::blend(down, zero, kx), B::blend(down, mkn, kb));
  s.ua = B::min(s.U, u);
  s.ka0 = B::min(s.K, k0);
  s.ka1 = B::min(s.K, k1);
  return s;
}

// single_terms() of all 16 intervals into t's one_* rows.
__attribute__((flatten)) void singles(BlendBounds& t) {
  const M all = B::valid(W);
  for (int c = 0; c < 3; ++c)
    for (int r = 0; r < 16; r += W) {
      const SingleTerms s = single_terms(t, c, r, all, true);
      B::storeu(t.one_u[c] + r, s.U);
      B::storeu(t.one_k[c] + r, s.K);
      B::storeu(t.one_ua[c] + r, s.ua);
      B::storeu(t.one_ka[0][c] + r, s.ka0);
      B::storeu(t.one_ka[1][c] + r, s.ka1);
    }
}

// Piece k of r (k < r.np) on table interval r0 + k: its bounds and ramp terms (single_terms()) and its
// largest curvature and |dκ/ds| (piece_curvature() over nodes r0 + k, r0 + k + 1: std::abs clears the
// sign bit; the quotient only where the table rises, else the rate stays 0) straight into the record.
__attribute__((flatten)) void record_singles(const BlendBounds& t, const double* k_at, const double* table, int r0,
                                             CubicRecord& r) {
  const D zero = B::set(0.0);
  for (int k = 0; k < r.np; k += W) {
    const M v = B::valid(r.np - k);
    const bool full = r.np - k >= W;
    const int q = r0 + k;
    for (int c = 0; c < 3; ++c) {
      const SingleTerms s = single_terms(t, c, q, v, full);
      B::storeu(r.u_abs[c] + k, s.U);
      B::storeu(r.k_abs[c] + k, s.K);
      B::storeu(r.ramp_u[0][c] + k, s.ua);
      B::storeu(r.ramp_u[1][c] + k, s.ua);
      B::storeu(r.ramp_k[0][c] + k, s.ka0);
      B::storeu(r.ramp_k[1][c] + k, s.ka1);
    }
    const D k0 = B::load(k_at + q, v, full), k1 = B::load(k_at + q + 1, v, full);
    const D t0 = B::load(table + q, v, full), t1 = B::load(table + q + 1, v, full);
    B::storeu(r.curvature + k, B::max(k1, B::max(k0, zero)));
    const D rate = B::max(B::div(B::abs(B::sub(k1, k0)), B::sub(t1, t0)), zero);
    B::storeu(r.curvature_rate + k, B::blend(B::gt(t1, t0), zero, rate));
  }
}

// BlendBounds' per-interval rows of one axis from its node values x (17, padded): the raw maxima of
// |x| and of its absolute second differences |(x[i−1] − 2·x[i]) + x[i+1]| (0 at the two end nodes),
// the signed extremes of x and the maxima of its own second differences; std::max(x[r], x[r + 1]) is
// B::max(x[r + 1], x[r]), std::min(x[r], x[r + 1]) is B::min(x[r + 1], x[r]).
// 17 nodes and room for whole packets: the rows are read up to node 16 + W − 1 (axis_rows() needs x set
// that far) and written up to 16 + W + 1
constexpr int node_lanes = 32;
// The lanes of v folded left to right with std::max (std::min), from its first lane.
NETSHAPE_SIMD_INLINE double lanes_max(D v) { return simd::fold_max<W>(v, B::lane(v, 0)); }
NETSHAPE_SIMD_INLINE double lanes_min(D v) { return simd::fold_min<W>(v, B::lane(v, 0)); }

// With `folds`, also the left folds of the five rows over the 16 intervals (std::max, the lo row
// std::min) into folds[0..4], in the row order above. A fold over packets (lane j over the intervals
// j, j + W, ...) and then over the lanes finds the same value; its bits are the left fold's when every
// element equal to the result has the same bits: always for the rows of absolute values (≥ +0; all node
// values finite, so no NaN), and for the signed rows when the result is not zero. When both signed
// extremes are ±0 every element is, and the left fold keeps the first; else (a non-finite node value,
// one signed extreme ±0) the left fold itself.
template <bool folds>
NETSHAPE_SIMD_INLINE void axis_rows(const double* x, double* amax, double* a2max, double* hi, double* lo, double* s2max,
                                    double* fold) {
  alignas(64) double a[node_lanes], da[node_lanes], dx[node_lanes];
  const D two = B::set(2.0), zero = B::set(0.0);
  for (int i = 0; i < 17; i += W) B::storeu(a + i, B::abs(B::loadu(x + i)));
  for (int i = 1; i < 17; i += W) {
    const auto second = [i, two](const double* v) NETSHAPE_SIMD_LAMBDA {
      return B::abs(B::add(B::sub(B::loadu(v + i - 1), B::mul(two, B::loadu(v + i))), B::loadu(v + i + 1)));
    };
    B::storeu(da + i, second(a));
    B::storeu(dx + i, second(x));
  }
  da[0] = da[16] = dx[0] = dx[16] = 0.0;
  D f[5];
  for (int r = 0; r < 16; r += W) {
    const auto upper = [r](const double* v) NETSHAPE_SIMD_LAMBDA { return B::max(B::loadu(v + r + 1), B::loadu(v + r)); };
    const D o[5] = {upper(a), upper(da), upper(x), B::min(B::loadu(x + r + 1), B::loadu(x + r)), upper(dx)};
    B::storeu(amax + r, o[0]);
    B::storeu(a2max + r, o[1]);
    B::storeu(hi + r, o[2]);
    B::storeu(lo + r, o[3]);
    B::storeu(s2max + r, o[4]);
    if constexpr (folds) {
      for (int q = 0; q < 5; ++q) f[q] = r == 0 ? o[q] : q == 3 ? B::min(o[q], f[q]) : B::max(o[q], f[q]);
    }
  }
  if constexpr (folds) {
    M bad = B::lt(zero, zero);  // a node value that is not finite (x − x is NaN)
    for (int i = 0; i < 17; i += W) {
      const D v = B::loadu(x + i);
      bad = B::lor(bad, B::ne(B::sub(v, v), zero));
    }
    const auto ordered = [](const double* row, bool is_min) NETSHAPE_SIMD_LAMBDA {
      double v = row[0];
      for (int r = 1; r < 16; ++r) v = is_min ? std::min(v, row[r]) : std::max(v, row[r]);
      return v;
    };
    if (B::any(bad)) {
      fold[0] = ordered(amax, false);
      fold[1] = ordered(a2max, false);
      fold[2] = ordered(hi, false);
      fold[3] = ordered(lo, true);
      fold[4] = ordered(s2max, false);
      return;
    }
    fold[0] = lanes_max(f[0]);
    fold[1] = lanes_max(f[1]);
    fold[4] = lanes_max(f[4]);
    double vh = lanes_max(f[2]), vl = lanes_min(f[3]);
    if (vh == 0.0 && vl == 0.0) {
      // every node value is ±0: no element is above (below) the first, which the left fold keeps
      vh = hi[0];
      vl = lo[0];
    } else {
      if (vh == 0.0) vh = ordered(hi, false);
      if (vl == 0.0) vl = ordered(lo, true);
    }
    fold[2] = vh;
    fold[3] = vl;
  }
}

// BlendBounds' rows from the unit tangents T and curvature vectors Kv at the 17 table nodes.
__attribute__((flatten)) void fill(BlendBounds& t, const double* T, const double* Kv) {
  for (int c = 0; c < 3; ++c) {
    alignas(64) double ts[node_lanes] = {}, ks[node_lanes] = {};
    for (int i = 0; i < 17; ++i) {
      ts[i] = T[3 * i + c];
      ks[i] = Kv[3 * i + c];
    }
    axis_rows<false>(ts, t.mu[c], t.du[c], t.tmax[c], t.tmin[c], t.st[c], nullptr);
    axis_rows<false>(ks, t.mk[c], t.dk[c], t.kmax[c], t.kmin[c], t.sk[c], nullptr);
  }
}

// Segment::blend()'s arc-length table and node frames (segment.cpp) and then fill() for a cubic block:
// the hodograph B'(u) = c0 + c1·u + c2·u², the table by 3-point Gauss-Legendre per interval of
// |B'| = sqrt(max(0, q0 + u·(q1 + u·(q2 + u·(q3 + u·q4))))) (intervals in the lanes), the unit tangent,
// curvature vector and curvature at the nodes u = i/16 (nodes in the lanes); Eigen's Vector3d sums
// (squaredNorm, dot) add as (x + y) + z. Returns false, with nothing written, for a Bézier symmetric
// about u = 1/2 (Segment::blend mirrors its second half; the caller takes that path).
__attribute__((flatten)) bool cubic_node(const double* P, double* table, double* k_at, BlendBounds& t,
                                         double (*whole)[10], double* finish) {
  double d0[3], d1[3], d2[3], c0[3], c1[3], c2[3];
  for (int c = 0; c < 3; ++c) {
    d0[c] = P[3 + c] - P[c];
    d1[c] = P[6 + c] - P[3 + c];
    d2[c] = P[9 + c] - P[6 + c];
    c0[c] = 3.0 * d0[c];
    c1[c] = 6.0 * (d1[c] - d0[c]);
    c2[c] = 3.0 * (d0[c] - 2.0 * d1[c] + d2[c]);
  }
  const auto dot = [](const double* a, const double* b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; };
  const double n0 = dot(d0, d0);
  if (dot(d1, d1) <= 1e-20 * n0 && std::abs(n0 - dot(d2, d2)) <= 1e-12 * n0) return false;
  const D zero = B::set(0.0), iota = B::iota(), sixteenth = B::set(16.0);
  // the table: |B'|² as a quartic, three nodes per interval
  const D q0 = B::set(dot(c0, c0)), q1 = B::set(2.0 * dot(c0, c1)), q2 = B::set(dot(c1, c1) + 2.0 * dot(c0, c2)),
          q3 = B::set(2.0 * dot(c1, c2)), q4 = B::set(dot(c2, c2));
  const auto speed = [&](D u) NETSHAPE_SIMD_LAMBDA {
    return B::sqrt(B::max(B::add(q0, B::mul(u, B::add(q1, B::mul(u, B::add(q2, B::mul(u, B::add(q3, B::mul(u, q4)))))))), zero));
  };
  constexpr double gx = 0.7745966692414834, w0 = 8.0 / 9.0, w1 = 5.0 / 9.0, h = 0.5 / 16.0;
  alignas(64) double piece[16];
  for (int i = 0; i < 16; i += W) {
    const D m = B::div(B::add(B::add(iota, B::set(i)), B::set(0.5)), sixteenth);
    const D hg = B::set(h * gx);
    B::storeu(piece + i, B::mul(B::set(h), B::add(B::mul(B::set(w0), speed(m)),
                                                 B::mul(B::set(w1), B::add(speed(B::sub(m, hg)), speed(B::add(m, hg)))))));
  }
  table[0] = 0;
  for (int i = 1; i <= 16; ++i) table[i] = table[i - 1] + piece[i - 1];
  // the node frames, per axis as rows over the nodes (padded: the lanes past node 16 are not read)
  alignas(64) double ts[3][node_lanes], ks[3][node_lanes], kk[node_lanes];  // (set up to node 16 + W − 1 below)
  for (int i = 0; i < 17; i += W) {
    const D u = B::div(B::add(iota, B::set(i)), sixteenth), u2 = B::mul(B::set(2.0), u);
    D v1[3], v2[3];
    for (int c = 0; c < 3; ++c) {
      v1[c] = B::add(B::set(c0[c]), B::mul(u, B::add(B::set(c1[c]), B::mul(u, B::set(c2[c])))));
      v2[c] = B::add(B::set(c1[c]), B::mul(u2, B::set(c2[c])));
    }
    const auto dot3 = [](const D* a, const D* b) NETSHAPE_SIMD_LAMBDA {
      return B::add(B::add(B::mul(a[0], b[0]), B::mul(a[1], b[1])), B::mul(a[2], b[2]));
    };
    const D sp2 = dot3(v1, v1);
    const M moving = B::gt(sp2, zero);
    const D isp = B::div(B::set(1.0), B::sqrt(sp2)), isp2 = B::mul(isp, isp);
    const D along = B::mul(dot3(v2, v1), isp2);
    D kv[3];
    for (int c = 0; c < 3; ++c) {
      kv[c] = B::mul(B::sub(v2[c], B::mul(along, v1[c])), isp2);
      B::storeu(ts[c] + i, B::blend(moving, zero, B::mul(v1[c], isp)));
      B::storeu(ks[c] + i, B::blend(moving, zero, kv[c]));
    }
    B::storeu(kk + i, B::blend(moving, zero, B::sqrt(dot3(kv, kv))));
  }
  for (int i = 0; i < 17; ++i) k_at[i] = kk[i];
  // finish_blend(): the largest curvature and |Δκ|/Δs between neighbouring nodes (0 where the table
  // does not rise); the values are ≥ +0, so with every input finite the largest has one bit pattern
  // whatever the order of the comparisons
  {
    M bad = B::lt(zero, zero);
    D kmax = zero, rate = zero;
    for (int i = 0; i < 16; i += W) {
      const D k0 = B::loadu(kk + i), k1 = B::loadu(kk + i + 1);
      const D t0 = B::loadu(table + i), t1 = B::loadu(table + i + 1);
      const D ds = B::sub(t1, t0), rises = B::blend(B::gt(ds, zero), B::set(1.0), ds);
      const M up = B::gt(ds, zero);
      rate = B::max(B::blend(up, zero, B::div(B::abs(B::sub(k1, k0)), rises)), rate);
      kmax = B::max(k0, kmax);
      bad = B::lor(bad, B::lor(B::ne(B::sub(k0, k0), zero), B::ne(B::sub(t0, t0), zero)));
    }
    const double k16 = kk[16], t16 = table[16];
    if (B::any(bad) || !std::isfinite(k16) || !std::isfinite(t16)) {
      finish[0] = -1.0;  // the caller runs finish_blend() itself
    } else {
      finish[0] = std::max(lanes_max(kmax), k16);
      finish[1] = lanes_max(rate);
    }
  }
  for (int c = 0; c < 3; ++c) {
    axis_rows<true>(ts[c], t.mu[c], t.du[c], t.tmax[c], t.tmin[c], t.st[c], whole[c]);
    axis_rows<true>(ks[c], t.mk[c], t.dk[c], t.kmax[c], t.kmin[c], t.sk[c], whole[c] + 5);
  }
  return true;
}

}  // namespace

extern const CubicRecordKernels cubic_record_kernel_table;
const CubicRecordKernels cubic_record_kernel_table{&freeze, &caps_reach, &junctions, &singles, &record_singles, &fill, &cubic_node, NETSHAPE_KERNEL_ISA_NAME};

}  // namespace netshape::motion::detail::NETSHAPE_KERNEL_ISA
