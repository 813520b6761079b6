// The smoothing stage's spline kernels (smoothing_kernels.hpp): one lane per knot span, as wide as the
// instruction set being compiled (simd::native_width), compiled once per instruction set by
// netshape_add_kernels. Only plain doubles cross between the kernels and the rest of the library.
//
// Each lane does the operations of the scalar definition in its order; its branches are masks, a value
// a branch would not have changed is kept by a blend (not by adding zero, which turns −0 into +0).
#include "core/simd.hpp"  // first: it wraps the intrinsic headers (see there)

#include "motion/kernels/smoothing_kernels.hpp"

namespace netshape::motion::detail::NETSHAPE_KERNEL_ISA {
namespace {

using B = simd::Batch<simd::native_width>;
using D = B::D;
using M = B::M;
constexpr int W = simd::native_width;

// −a, exactly (the sign flipped, also for ±0)
NETSHAPE_SIMD_INLINE D neg(D a) { return B::sub(B::set(-0.0), a); }

// Spline::power_basis() for spans k0..k1, W spans per step: lane l of a step is span k + l. The knot
// differences d[q] = t[k − 3 + q] − t[k] of W consecutive spans are W consecutive knots each.
__attribute__((flatten)) void power_basis(const double* t, int k0, int k1, double* pb) {
  const D zero = B::set(0.0), one = B::set(1.0);
  for (int k = k0; k <= k1; k += W) {
    const int n = k1 - k + 1;  // spans left
    const bool full = n >= W;
    const M v = B::valid(n);
    const D tk = B::load(t + k, v, full);
    const M live = B::gt(B::load(t + k + 1, v, full), tk);
    D d[8];
    for (int q = 0; q < 8; ++q) d[q] = B::sub(B::load(t + k - 3 + q, v, full), tk);
    D N[4][4];  // N[r][j]: coefficient of x^j in N_{k−p+r, p}
    for (int r = 0; r < 4; ++r)
      for (int j = 0; j < 4; ++j) N[r][j] = zero;
    N[0][0] = one;
    for (int p = 1; p <= 3; ++p) {
      D Mx[4][4];
      for (int r = 0; r < 4; ++r)
        for (int j = 0; j < 4; ++j) Mx[r][j] = zero;
      for (int r = 0; r <= p; ++r) {
        const D a0 = d[3 - p + r], a1 = d[3 + r], b0 = d[4 - p + r], b1 = d[4 + r];
        if (r >= 1) {  // (x − a0)/(a1 − a0) · N[r − 1] where a1 > a0
          const M on = B::gt(a1, a0);
          const D f = B::div(one, B::sub(a1, a0));
          const D* nn = N[r - 1];
          const D add[4] = {B::mul(f, B::mul(neg(a0), nn[0])), B::mul(f, B::sub(nn[0], B::mul(a0, nn[1]))),
                            B::mul(f, B::sub(nn[1], B::mul(a0, nn[2]))), B::mul(f, B::sub(nn[2], B::mul(a0, nn[3])))};
          for (int j = 0; j < 4; ++j) Mx[r][j] = B::blend(on, Mx[r][j], B::add(Mx[r][j], add[j]));
        }
        if (r < p) {  // (b1 − x)/(b1 − b0) · N[r] where b1 > b0
          const M on = B::gt(b1, b0);
          const D f = B::div(one, B::sub(b1, b0));
          const D* nn = N[r];
          const D add[4] = {B::mul(f, B::mul(b1, nn[0])), B::mul(f, B::sub(B::mul(b1, nn[1]), nn[0])),
                            B::mul(f, B::sub(B::mul(b1, nn[2]), nn[1])), B::mul(f, B::sub(B::mul(b1, nn[3]), nn[2]))};
          for (int j = 0; j < 4; ++j) Mx[r][j] = B::blend(on, Mx[r][j], B::add(Mx[r][j], add[j]));
        }
      }
      for (int r = 0; r < 4; ++r)
        for (int j = 0; j < 4; ++j) N[r][j] = Mx[r][j];
    }
    // pb[k + l][4·j + r] = N[r][j] in lane l, 0 for an empty span
    alignas(64) double out[16][W];
    for (int j = 0; j < 4; ++j)
      for (int r = 0; r < 4; ++r) B::storeu(out[4 * j + r], B::blend(live, zero, N[r][j]));
    const int lanes = full ? W : n;
    for (int l = 0; l < lanes; ++l) {
      double* b = pb + 16 * static_cast<long>(k + l);
      for (int e = 0; e < 16; ++e) b[e] = out[e][l];
    }
  }
}

// dist2() of one point (x, y) to the W segments of a step
NETSHAPE_SIMD_INLINE D dist2(D x, D y, D ax, D ay, D dx, D dy, D il2) {
  const D zero = B::set(0.0), one = B::set(1.0);
  const D rx = B::sub(x, ax), ry = B::sub(y, ay);
  const D c = B::mul(B::add(B::mul(rx, dx), B::mul(ry, dy)), il2);
  const D t = B::blend(B::lt(c, zero), B::blend(B::lt(one, c), c, one), zero);
  const D ex = B::sub(rx, B::mul(t, dx)), ey = B::sub(ry, B::mul(t, dy));
  return B::add(B::mul(ex, ex), B::mul(ey, ey));
}

// Two points against W segments per step, lanes past hi masked (they keep the minima at 1e300).
// std::min(m, v) is B::min(v, m) and std::max(a, b) is B::max(b, a).
__attribute__((flatten)) void pair_window(const double* p, const SegRows& s, long lo, long hi, const double* sag,
                                          double* D0, double* D1, double* mins) {
  const D big = B::set(1e300);
  const D x0 = B::set(p[0]), y0 = B::set(p[1]), x1 = B::set(p[2]), y1 = B::set(p[3]);
  D best2 = big, m0 = big, m1 = big, best = big, smin = big;
  for (long q = lo; q <= hi; q += W) {
    const long n = hi - q + 1;
    const bool full = n >= W;
    const M v = B::valid(static_cast<int>(full ? W : n));
    const D ax = B::load(s.ax + q, v, full), ay = B::load(s.ay + q, v, full);
    const D dx = B::load(s.dx + q, v, full), dy = B::load(s.dy + q, v, full), il2 = B::load(s.il2 + q, v, full);
    const D d0 = dist2(x0, y0, ax, ay, dx, dy, il2), d1 = dist2(x1, y1, ax, ay, dx, dy, il2);
    B::store(D0 + (q - lo), d0, v, full);
    B::store(D1 + (q - lo), d1, v, full);
    const D mx = B::max(d1, d0);
    // a lane past hi offers 1e300, which leaves every minimum as it is
    const auto in = [v, big](D a) NETSHAPE_SIMD_LAMBDA { return B::blend(v, big, a); };
    best2 = B::min(in(mx), best2);
    m0 = B::min(in(d0), m0);
    m1 = B::min(in(d1), m1);
    if (sag != nullptr) {
      const D sg = B::load(sag + q, v, full);
      best = B::min(in(B::add(B::sqrt(mx), sg)), best);
      smin = B::min(in(sg), smin);
    }
  }
  mins[0] = simd::fold_min<W>(best2, 1e300);
  mins[1] = simd::fold_min<W>(m0, 1e300);
  mins[2] = simd::fold_min<W>(m1, 1e300);
  if (sag != nullptr) {
    mins[3] = simd::fold_min<W>(best, 1e300);
    mins[4] = simd::fold_min<W>(smin, 1e300);
  }
}

// run_bound()'s parts: the end points' values, W segments per step, then the cuts at the bisectors
// and their values for the segments on both sides, W vertices per step (loads at q + 1 for the
// segment after the vertex)
__attribute__((flatten)) void run_parts(const double* c, const SegRows& s, long lo, long hi, const double* sag,
                                        const double* D0, const double* D1, double* V0, double* V1, double* VN,
                                        double* VX) {
  const D zero = B::set(0.0), one = B::set(1.0);
  // val(d2, q) for the W values from segment q on
  const auto val = [sag](D d2, long q, M v, bool full) NETSHAPE_SIMD_LAMBDA {
    return sag == nullptr ? d2 : B::add(B::sqrt(d2), B::load(sag + q, v, full));
  };
  for (long q = lo; q <= hi; q += W) {
    const long n = hi - q + 1;
    const bool full = n >= W;
    const M v = B::valid(static_cast<int>(full ? W : n));
    const long i = q - lo;
    B::store(V0 + i, val(B::load(D0 + i, v, full), q, v, full), v, full);
    B::store(V1 + i, val(B::load(D1 + i, v, full), q, v, full), v, full);
  }
  const D c0x = B::set(c[0]), c0y = B::set(c[1]);
  const D ex = B::set(c[2] - c[0]), ey = B::set(c[3] - c[1]);
  for (long q = lo; q < hi; q += W) {
    const long n = hi - q;  // vertices left
    const bool full = n >= W;
    const M v = B::valid(static_cast<int>(full ? W : n));
    const long i = q - lo;
    const D wx = B::load(s.wx + q, v, full), wy = B::load(s.wy + q, v, full);
    const D bx = B::load(s.ax + q + 1, v, full), by = B::load(s.ay + q + 1, v, full);
    const D ax = B::sub(bx, c0x), ay = B::sub(by, c0y);
    D t = B::div(B::sub(B::mul(ax, wy), B::mul(ay, wx)), B::sub(B::mul(ex, wy), B::mul(ey, wx)));
    t = B::blend(B::ge(t, zero), zero, t);  // NaN too
    t = B::blend(B::le(t, one), one, t);
    const D x = B::add(c0x, B::mul(t, ex)), y = B::add(c0y, B::mul(t, ey));
    const D dn = dist2(x, y, B::load(s.ax + q, v, full), B::load(s.ay + q, v, full), B::load(s.dx + q, v, full),
                       B::load(s.dy + q, v, full), B::load(s.il2 + q, v, full));
    const D dx = dist2(x, y, bx, by, B::load(s.dx + q + 1, v, full), B::load(s.dy + q + 1, v, full),
                       B::load(s.il2 + q + 1, v, full));
    B::store(VN + i, val(dn, q, v, full), v, full);
    B::store(VX + i, val(dx, q + 1, v, full), v, full);
  }
}

// Spline::span_near(): u's knot span (t[k] ≤ u < t[k + 1], the last one for u ≥ t[m]), searched from
// span k first, then by bisection as std::upper_bound over t[3..m] does it (the first knot above u).
NETSHAPE_SIMD_INLINE int span_of(const FootSpline& sp, double u, int k) {
  const double* t = sp.t;
  const int m = sp.m;
  if (u >= t[m]) return m - 1;
  k = k < 3 ? 3 : (m - 1 < k ? m - 1 : k);
  for (int step = 0; step < 4; ++step) {
    if (u < t[k]) {
      if (k == 3) return 3;
      --k;
    } else if (u >= t[k + 1]) {
      ++k;
    } else {
      return k;
    }
  }
  int first = 3, count = m - 2;  // [t + 3, t + m + 1)
  while (count > 0) {
    const int half = count / 2;
    if (!(u < t[first + half])) {
      first += half + 1;
      count -= half + 1;
    } else {
      count = half;
    }
  }
  return first - 1;
}

// Lane l of m as a bool.
NETSHAPE_SIMD_INLINE void lanes_of(M m, bool* out) {
  alignas(64) double l[W];
  B::storeu(l, B::blend(m, B::set(0.0), B::set(1.0)));
  for (int i = 0; i < W; ++i) out[i] = l[i] != 0.0;
}

// fit_run()'s foot-point Newton steps, W points per step. The span search and the fetch of a span's
// coefficients are per lane; the evaluations and steps are Spline::eval()'s and fit_run()'s operations
// lane by lane, a lane that has stopped keeping its values by blends.
__attribute__((flatten)) void foot_points(const FootSpline& sp, int n, double* u, int* k, const double* px,
                                          const double* py, double* res) {
  const D zero = B::set(0.0), two = B::set(2.0), three = B::set(3.0), six = B::set(6.0);
  const D L = B::set(sp.L), step_hi = B::set(0.25 * sp.mean), step_lo = B::set(-0.25 * sp.mean), tiny = B::set(1e-9);
  // std::clamp(v, lo, hi): v < lo gives lo, else hi < v gives hi, else v
  const auto clamp = [](D v, D lo, D hi) NETSHAPE_SIMD_LAMBDA { return B::blend(B::lt(v, lo), B::blend(B::lt(hi, v), v, hi), lo); };
  for (int i0 = 0; i0 < n; i0 += W) {
    const int nl = n - i0 < W ? n - i0 : W;
    const bool full = nl == W;
    const M v = B::valid(nl);
    alignas(64) double U[W], C[8][W], T[W], T1[W];
    int K[W], K0[W];
    for (int l = 0; l < W; ++l) {
      U[l] = l < nl ? u[i0 + l] : 0.0;
      K[l] = l < nl ? k[i0 + l] : 3;
    }
    const D x0 = B::load(px + i0, v, full), y0 = B::load(py + i0, v, full);
    D s0x, s0y, s1x, s1y, s2x, s2y;
    // Spline::eval() at U in the lanes of `want`: span search, coefficients, then the polynomials.
    // After the first evaluation C, T and T1 hold each lane's span's coefficients and knots t[K],
    // t[K + 1]; a lane whose U is still in its span [t[K], t[K + 1]) is where span_near() would find it
    // at its first look, and the others search and fetch one at a time.
    bool fetched = false;
    const auto eval = [&](M want) NETSHAPE_SIMD_LAMBDA {
      const D Uv = B::loadu(U);
      const M need = fetched ? B::land(want, B::lnot(B::land(B::ge(Uv, B::loadu(T)), B::lt(Uv, B::loadu(T1))))) : want;
      if (B::any(need)) {
        bool search[W];
        lanes_of(need, search);
        for (int l = 0; l < W; ++l) {
          if (!search[l]) continue;
          const int kn = span_of(sp, U[l], K[l]);
          if (fetched && kn == K[l]) continue;
          K[l] = kn;
          const double* c = sp.pw + 8 * static_cast<long>(kn);
          for (int j = 0; j < 8; ++j) C[j][l] = c[j];
          T[l] = sp.t[kn];
          T1[l] = sp.t[kn + 1];
        }
      }
      fetched = true;
      const D x = B::sub(Uv, B::loadu(T));
      const D c0x = B::loadu(C[0]), c0y = B::loadu(C[1]), c1x = B::loadu(C[2]), c1y = B::loadu(C[3]);
      const D c2x = B::loadu(C[4]), c2y = B::loadu(C[5]), c3x = B::loadu(C[6]), c3y = B::loadu(C[7]);
      s0x = B::add(c0x, B::mul(x, B::add(c1x, B::mul(x, B::add(c2x, B::mul(x, c3x))))));
      s0y = B::add(c0y, B::mul(x, B::add(c1y, B::mul(x, B::add(c2y, B::mul(x, c3y))))));
      s1x = B::add(c1x, B::mul(x, B::add(B::mul(two, c2x), B::mul(x, B::mul(three, c3x)))));
      s1y = B::add(c1y, B::mul(x, B::add(B::mul(two, c2y), B::mul(x, B::mul(three, c3y)))));
      const D x6 = B::mul(six, x);
      s2x = B::add(B::mul(two, c2x), B::mul(x6, c3x));
      s2y = B::add(B::mul(two, c2y), B::mul(x6, c3y));
    };
    // the Newton step from the last evaluation: where fp > 0 (ok), the new parameter into un
    const auto newton = [&](M& ok, D& du, D& un) NETSHAPE_SIMD_LAMBDA {
      const D rx = B::sub(s0x, x0), ry = B::sub(s0y, y0);
      const D fp = B::add(B::add(B::mul(s1x, s1x), B::mul(s1y, s1y)), B::add(B::mul(rx, s2x), B::mul(ry, s2y)));
      ok = B::gt(fp, zero);
      const D dot = B::add(B::mul(rx, s1x), B::mul(ry, s1y));
      du = clamp(B::div(B::sub(B::set(-0.0), dot), fp), step_lo, step_hi);
      un = clamp(B::add(B::loadu(U), du), zero, L);
    };
    const D u_in = B::loadu(U);
    eval(B::valid(W));
    for (int l = 0; l < W; ++l) K0[l] = K[l];
    const auto dist = [&](D ax, D ay) NETSHAPE_SIMD_LAMBDA {
      const D rx = B::sub(ax, x0), ry = B::sub(ay, y0);
      return B::sqrt(B::add(B::mul(rx, rx), B::mul(ry, ry)));
    };
    const D r_old = dist(s0x, s0y);
    M ok;
    D du, un;
    newton(ok, du, un);
    // the second evaluation where the first step was taken
    B::storeu(U, B::blend(ok, u_in, un));
    D fx = s0x, fy = s0y;  // the last evaluation's point per lane
    if (B::any(ok)) {
      eval(ok);
      fx = B::blend(ok, fx, s0x);
      fy = B::blend(ok, fy, s0y);
      M ok1;
      D du1, un1;
      newton(ok1, du1, un1);
      // a second step only after a first one of at least 1e-9, and where fp > 0
      ok1 = B::land(B::land(ok, B::lnot(B::lt(B::abs(du), tiny))), ok1);
      if (B::any(ok1)) {
        B::storeu(U, B::blend(ok1, B::loadu(U), un1));
        eval(ok1);
        fx = B::blend(ok1, fx, s0x);
        fy = B::blend(ok1, fy, s0y);
      }
    }
    const D r = dist(fx, fy);
    const M keep = B::le(r, r_old);
    B::store(u + i0, B::blend(keep, u_in, B::loadu(U)), v, full);
    B::store(res + i0, B::blend(keep, r_old, r), v, full);
    bool kept[W];
    lanes_of(keep, kept);
    for (int l = 0; l < nl; ++l) k[i0 + l] = kept[l] ? K[l] : K0[l];
  }
}

}  // namespace

extern const SmoothingKernels smoothing_kernel_table;
const SmoothingKernels smoothing_kernel_table{&power_basis, &pair_window, &run_parts, &foot_points, NETSHAPE_KERNEL_ISA_NAME};

}  // namespace netshape::motion::detail::NETSHAPE_KERNEL_ISA
