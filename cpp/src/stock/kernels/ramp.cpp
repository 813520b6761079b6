// Flat and ball ramps and level lines of the Z-map sweep, written once over simd::Batch<W> and
// compiled once per instruction set by netshape_add_kernels (kernels/sweep_kernels.hpp).
#include "core/simd.hpp"  // first: it wraps the intrinsic headers (see there)

#include <cstdint>

#include "stock/kernels/sweep_kernels.hpp"

namespace netshape::stock::kernels::NETSHAPE_KERNEL_ISA {
namespace {
using simd::Batch;
using simd::prefetch_for_write;

/// Lanes of the ramp kernels: the widest pack, one node at a time on the baseline.
constexpr int kWidth = simd::native_width >= 4 ? simd::native_width : 1;
constexpr int kFlat = 0, kBall = 1;

// Node spans of the rows i0 … i0 + n − 1 of a move (W rows at a time): per row the X interval of the
// stadium (union of the two end discs and the strip along the segment), with a slack of kSpanSlack
// index units outward, as node columns clamped to [jlo, jhi]; j0s[k] > j1s[k] when the row has none.
// Conservative, not exact: the per-node test of ramp_move decides which nodes the cutter covers.
template <int W>
void row_spans(const SpanSetup& q, int i0, int n, int jlo, int jhi, int* j0s, int* j1s) {
  using B = Batch<W>;
  using D = typename B::D;
  using M = typename B::M;
  const D vr2 = B::set(q.r2), vR = B::set(q.r), vax = B::set(q.ax), vay = B::set(q.ay), vbx = B::set(q.bx),
          vby = B::set(q.by), vex = B::set(q.ex), vey = B::set(q.ey), vlen = B::set(q.len), viex = B::set(q.iex),
          viey = B::set(q.iey), vy0 = B::set(q.y0), vdy = B::set(q.dy), vx0 = B::set(q.x0), vidx = B::set(q.idx),
          vzero = B::set(0.0), vinf = B::set(inf), vninf = B::set(-inf), vhalf_lo = B::set(0.5 + kSpanSlack),
          vhalf_hi = B::set(0.5 - kSpanSlack), vjlo = B::set(jlo), vjhi = B::set(jhi),
          vjlo1 = B::set(jlo - 1.0), vjhi1 = B::set(jhi + 1.0), vtiny = B::set(kSpanSlack * q.dy);
  alignas(64) double lo[B::W], hi[B::W];
  for (int k = 0; k < n; k += B::W) {
    const D y = B::add(vy0, B::mul(B::add(B::set(i0 + k + 0.5), B::iota()), vdy));
    const D yy = B::sub(y, vay), yb = B::sub(y, vby);
    // end discs
    const D wa = B::sub(vr2, B::mul(yy, yy)), wb = B::sub(vr2, B::mul(yb, yb));
    const D ha = B::sqrt(B::max(wa, vzero)), hb = B::sqrt(B::max(wb, vzero));
    const M oka = B::ge(wa, vzero), okb = B::ge(wb, vzero);
    D xlo = B::min(B::blend(oka, vinf, B::sub(vax, ha)), B::blend(okb, vinf, B::sub(vbx, hb)));
    D xhi = B::max(B::blend(oka, vninf, B::add(vax, ha)), B::blend(okb, vninf, B::add(vbx, hb)));
    // strip: |yy·ex − qx·ey| ≤ R and 0 ≤ qx·ex + yy·ey ≤ len, qx = x − A_x
    D slo = vninf, shi = vinf;
    const D te = B::mul(yy, vex), tf = B::mul(yy, vey);
    if (q.use_ey) {
      const D a = B::mul(B::sub(te, vR), viey), b = B::mul(B::add(te, vR), viey);
      slo = B::max(slo, B::min(a, b));
      shi = B::min(shi, B::max(a, b));
    } else {  // along X: the strip holds the rows with |yy·ex| ≤ R
      const M in = B::land(B::le(te, B::add(vR, vtiny)), B::ge(te, B::sub(vzero, B::add(vR, vtiny))));
      slo = B::blend(in, vinf, slo);
    }
    if (q.use_ex) {
      const D a = B::mul(B::sub(vzero, tf), viex), b = B::mul(B::sub(vlen, tf), viex);
      slo = B::max(slo, B::min(a, b));
      shi = B::min(shi, B::max(a, b));
    } else {  // along Y: the strip holds the rows with 0 ≤ yy·ey ≤ len
      const M in = B::land(B::ge(tf, B::sub(vzero, vtiny)), B::le(tf, B::add(vlen, vtiny)));
      slo = B::blend(in, vinf, slo);
    }
    const M oks = B::le(slo, shi);
    xlo = B::min(xlo, B::blend(oks, vinf, B::add(vax, slo)));
    xhi = B::max(xhi, B::blend(oks, vninf, B::add(vax, shi)));
    // node columns with centre in [xlo, xhi] (j + ½ = (x − x0)/dx), widened by the slack, clamped
    const D ja = B::ceil(B::sub(B::mul(B::sub(xlo, vx0), vidx), vhalf_lo));
    const D jb = B::floor(B::sub(B::mul(B::sub(xhi, vx0), vidx), vhalf_hi));
    B::storeu(lo, B::min(B::max(ja, vjlo), vjhi1));
    B::storeu(hi, B::max(B::min(jb, vjhi), vjlo1));
    const int m = n - k < B::W ? n - k : B::W;
    for (int l = 0; l < m; ++l) {
      j0s[k + l] = static_cast<int>(lo[l]);
      j1s[k + l] = static_cast<int>(hi[l]);
    }
  }
}

// The walk shared by ramp_move and level_move: rows i0 … i1; per row the nodes of the row span
// [j0, j1] are taken in chunks of W nodes starting at column multiples of W (nodes of a chunk outside
// the stadium get ok = false from the exact test, so they do not change). While row i is computed,
// row i + kAhead is prefetched, one cache line per chunk (spread out: a burst of prefetches stalls on
// fill buffers). Per chunk, chunk(tq, sp, hk, valid, z, ok) gets the foot point along the move and
// the signed distance from it (tq = qx·ex + qy·ey, sp = qy·ex − qx·ey) and the heights; it returns
// false when no node of the chunk can be lowered, else the tip z and the nodes it covers.
template <int W, class Chunk>
NETSHAPE_SIMD_INLINE void move_rows(const MoveArgs& a, MoveOut& out, const Chunk& chunk) {
  using B = Batch<W>;
  using D = typename B::D;
  using M = typename B::M;
  double* const H = a.H;
  const int nx = a.nx, i0 = a.i0, i1 = a.i1, cmin = a.cmin;
  const int *j0s = a.j0s, *j1s = a.j1s;
  const double *tqx = a.tqx, *spx = a.spx;
  const LineSetup& s = a.s;
  const double bottom = a.bottom;
  const D vbot = B::set(bottom), vzero = B::set(0.0);
  D vol = vzero;
  std::int64_t cnt = 0, visited = 0;
  for (int d = 0; d < kAhead && i0 + d <= i1; ++d)
    if (j0s[d] <= j1s[d])
      simd::prefetch_span_for_write(H + static_cast<std::int64_t>(i0 + d) * nx + j0s[d], j1s[d] - j0s[d] + 1);
  for (int i = i0; i <= i1; ++i) {
    const int r = i - i0;
    const int j0 = j0s[r], j1 = j1s[r];
    const bool pf = i + kAhead <= i1 && j0s[r + kAhead] <= j1s[r + kAhead];
    const double* hp = pf ? H + static_cast<std::int64_t>(i + kAhead) * nx : H;
    int pc = pf ? j0s[r + kAhead] : 0;
    const int pend = pf ? j1s[r + kAhead] : -1;
    if (j0 <= j1) {
      visited += j1 - j0 + 1;
      const double qy = (a.y0 + (i + 0.5) * a.dy) - s.ay;  // ZMap::node_y(i) − A_y
      const D ty = B::set(qy * s.ey), sy = B::set(qy * s.ex);
      double* h = H + static_cast<std::int64_t>(i) * nx;
      for (int c = j0 - j0 % B::W; c <= j1; c += B::W) {
        if (pc <= pend) {
          prefetch_for_write(hp + pc);
          pc += 8;
        }
        const bool full = c + B::W <= nx;
        const M valid = B::valid(nx - c);
        const D hk = B::load(h + c, valid, full);
        const D tq = B::add(B::load(tqx + (c - cmin), valid, true), ty);
        const D sp = B::sub(sy, B::load(spx + (c - cmin), valid, true));
        D z;
        M ok;
        if (!chunk(tq, sp, hk, valid, z, ok)) continue;
        const D zb = B::max(z, vbot);
        const M low = B::land(ok, B::lt(zb, hk));
        if (!B::any(low)) continue;
        const D nh = B::blend(low, hk, zb);
        vol = B::add(vol, B::sub(hk, nh));
        cnt += B::count(low);
        B::store(h + c, nh, valid, full);
      }
    }
    for (; pc <= pend; pc += 8) prefetch_for_write(hp + pc);
  }
  out.vol += B::sum(vol);
  out.lowered += cnt;
  out.visited += visited;
}

// One whole move (a ramp: m ≠ 0, not vertical; Up: m > 0), walked by move_rows. Per node, the same
// arithmetic in the same order as the NumPy reference (tests/python/stock/zmap_reference.py): bit-identical heights.
template <int W, int Kind, bool Up>
void ramp_move(const MoveArgs& a, MoveOut& out) {
  using B = Batch<W>;
  using D = typename B::D;
  using M = typename B::M;
  const LineSetup& s = a.s;
  const double R = a.R;
  const D vR = B::set(R), vr2 = B::set(R * R), vlen = B::set(s.len), vaz = B::set(s.az),
                      vm = B::set(s.m), vkb = B::set(s.kball), vzero = B::set(0.0), vhir = B::set(0.5 / R),
                      vmargin = B::set(-kSkipMargin);
  auto chunk = [=](D tq, D sp, D hk, M valid, D& z,
                   M& ok) NETSHAPE_SIMD_LAMBDA {
    // skip the chunk if no node can be lowered: h ≤ (lowest tip z over |σ − τ_q| ≤ R) + lift bound
    D zt = Up ? B::mul(vm, B::max(B::sub(tq, vR), vzero)) : B::mul(vm, B::min(B::add(tq, vR), vlen));
    zt = B::add(vaz, zt);
    if (Kind == kBall) zt = B::add(zt, B::mul(B::mul(sp, sp), vhir));
    if (!B::any(B::gt(B::sub(hk, zt), vmargin))) return false;
    // travel window σ ∈ [lo, hi] where the node is under the cutter
    const D rho2 = B::sub(vr2, B::mul(sp, sp));
    const D rho = B::sqrt(B::max(rho2, vzero));
    const D lo = B::max(B::sub(tq, rho), vzero);
    const D hi = B::min(B::add(tq, rho), vlen);
    ok = B::land(B::land(B::ge(rho2, vzero), B::le(lo, hi)), valid);
    if (Kind == kFlat) {
      z = B::add(vaz, B::mul(vm, Up ? lo : hi));
    } else {  // σ* = clamp(τ_q − m·ρ/sqrt(1 + m²), lo, hi)
      const D sig = B::min(B::max(B::sub(tq, B::mul(vkb, rho)), lo), hi);
      const D u = B::sub(sig, tq);
      const D w = B::sub(rho2, B::mul(u, u));
      z = B::sub(B::add(B::add(vaz, B::mul(vm, sig)), vR), B::sqrt(B::max(w, vzero)));
    }
    return true;
  };
  move_rows<W>(a, out, chunk);
}

// One whole level move (m = 0, not vertical), flat or ball, walked by move_rows: the point of the
// segment nearest to the node, u = τ_q − clamp(τ_q, 0, L), d² = s² + u²; flat z = A_z, ball
// z = A_z + R − sqrt(R² − d²), where d² ≤ R². Per node the arithmetic of the NumPy reference
// (level branch) in its order: bit-identical heights.
template <int W, int Kind>
void level_move(const MoveArgs& a, MoveOut& out) {
  using B = Batch<W>;
  using D = typename B::D;
  using M = typename B::M;
  const LineSetup& s = a.s;
  const double R = a.R;
  const D vr2 = B::set(R * R), vlen = B::set(s.len), vaz = B::set(s.az), vzero = B::set(0.0),
                      vhir = B::set(0.5 / R), vmargin = B::set(-kSkipMargin), vazR = B::set(s.az + R);
  auto chunk = [=](D tq, D sp, D hk, M valid, D& z,
                   M& ok) NETSHAPE_SIMD_LAMBDA {
    const D u = B::sub(tq, B::min(B::max(tq, vzero), vlen));
    const D d2 = B::add(B::mul(sp, sp), B::mul(u, u));
    ok = B::land(B::le(d2, vr2), valid);
    if (Kind == kFlat) {
      z = vaz;
    } else {
      // skip the chunk if no node can be lowered: h ≤ A_z + d²/(2R) (≤ the lift) + margin
      if (!B::any(B::gt(B::sub(hk, B::add(vaz, B::mul(d2, vhir))), vmargin))) return false;
      z = B::sub(vazR, B::sqrt(B::max(B::sub(vr2, d2), vzero)));
    }
    return true;
  };
  move_rows<W>(a, out, chunk);
}

void spans(const SpanSetup& q, int i0, int n, int jlo, int jhi, int* j0s, int* j1s) {
  row_spans<kWidth>(q, i0, n, jlo, jhi, j0s, j1s);
}
}  // namespace

extern const RampKernels ramp_kernels;
const RampKernels ramp_kernels{&spans,
                               {{&level_move<kWidth, kFlat>, &ramp_move<kWidth, kFlat, true>,
                                 &ramp_move<kWidth, kFlat, false>},
                                {&level_move<kWidth, kBall>, &ramp_move<kWidth, kBall, true>,
                                 &ramp_move<kWidth, kBall, false>}}};

}  // namespace netshape::stock::kernels::NETSHAPE_KERNEL_ISA
