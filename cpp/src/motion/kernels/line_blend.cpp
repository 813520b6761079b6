// The planner's line-blend kernels (kernels/line_blend_kernels.hpp): the array work of a corner blend between two
// lines, 4 lanes wide (one per piece), compiled once per instruction set by netshape_add_kernels.
// Only plain doubles and Vec3 (no vectorisable Eigen type, whose alignment differs between the
// copies) cross between the kernels and the rest of the library, and both entry points are flattened,
// so no Eigen function is left out of line for the linker to share with baseline code.
#include "core/simd.hpp"  // first: it wraps the intrinsic headers (see there)

#include <algorithm>
#include <cmath>
#include <limits>

#include "motion/kernels/line_blend_kernels.hpp"

#if defined(__AVX512F__)
// The blends are 4 lanes wide, which AVX2 already runs as one packet, and Eigen's AVX-512 packets fuse
// multiply-adds (the AVX2 and baseline copies give the same bits, an AVX-512 one would not): the
// AVX-512 copy hands out the AVX2 kernels.
namespace netshape::motion::detail {
namespace avx2 {
int build(const LineBlendTables& T, Segment& whole, const Vec3& p0, const Vec3& vtx, const Vec3& p3, const Vec3& u1,
          const Vec3& u2, double d, long source, const Vec3& A, const Vec3& V, const Vec3& inv_acc, double vfeed,
          double v_prev, LineBlendRecord& r);
double freeze(LineBlendRecord& r, double vs, double wt, const Vec3& A, double t_start);
}  // namespace avx2
namespace avx512 {
extern const LineBlendKernels line_blend_kernel_table;
const LineBlendKernels line_blend_kernel_table{&avx2::build, &avx2::freeze, "avx2"};
}  // namespace avx512
}  // namespace netshape::motion::detail
#else
namespace netshape::motion::detail::NETSHAPE_KERNEL_ISA {
namespace {

constexpr double inf = std::numeric_limits<double>::infinity();
using PieceArr = Eigen::Array<double, n_cuts_lines, 1>;  // per piece (a lane each)
using A24 = Eigen::Array<double, 24, 1>;
using A12 = Eigen::Array<double, 12, 1>;
using AN = Eigen::Array<double, n_cut_lanes, 1>;  // per piece end (padding lanes: node 16 again)
using A8 = Eigen::Array<double, 8, 1>;

// The blend at its piece ends: unit tangent ta·u1 + tb·u2 and curvature κ [1/mm].
struct Nodes {
  AN ta, tb, kappa;
  double kappa_mid = 0.0;         // κ at node 8 (the largest)
  double c = 1.0, inv_sin = 0.0;  // cos θ and 1/sin θ of the turn
};

// The symmetric blend between two lines: P0 = V − d·u1, P1 = P2 = V, P3 = V + d·u2 (u1, u2 unit).
// Its hodograph is B'(u) = 3d·((1 − u)²·u1 + u²·u2) and B''(u) = 6d·(−(1 − u)·u1 + u·u2), so
// |B'|² = 9d²·g2 with g2 = a² + b² + 2ab·cos θ, B' × B'' = 18d²·u(1 − u)·(u1 × u2) and the curvature
// is κ = (2 sin θ/(3d))·u(1 − u)/g2^{3/2}: everything depends on u and θ only, and node 16 − i mirrors
// node i. Fills s in place (the fields of Segment::blend) and the piece-end values nd.
inline void blend_lines(const LineBlendTables& T, Segment& s, const Vec3& p0, const Vec3& vtx, const Vec3& p3,
                        const Vec3& u1, const Vec3& u2, double d, long source, Nodes& nd) {
  s.kind = SegmentKind::blend;
  s.ctrl = {p0, vtx, vtx, p3};
  s.source = source;
  s.trim_start = s.trim_end = 0.0;
  const double c = u1.dot(u2), sn = u1.cross(u2).norm();  // |u1 × u2| keeps small turns accurate
  // arc length: 3-point Gauss-Legendre per interval of |B'| = 3d·sqrt(g2); first half, mirrored
  constexpr double w0 = 8.0 / 9.0, w1 = 5.0 / 9.0, h = 0.5 / 16.0;
  const A24 sp = (Eigen::Map<const A24>(T.gp) + Eigen::Map<const A24>(T.gq) * c).max(0.0).sqrt();
  const double scale = 3.0 * d * h;
  const A8 piece = scale * (w0 * sp.head<8>() + w1 * (sp.segment<8>(8) + sp.tail<8>()));  // centre, left, right
  s.table[0] = 0;
  for (int i = 1; i <= 8; ++i) s.table[i] = s.table[i - 1] + piece[i - 1];
  for (int i = 9; i <= 16; ++i) s.table[i] = s.table[i - 1] + piece[16 - i];
  // curvature at the nodes 0..8 (the second half mirrors them; lanes 9..11 are padding) and at the
  // piece ends
  const double ks = 2.0 * sn / (3.0 * d);
  const A12 iG = (Eigen::Map<const A12>(T.np) + Eigen::Map<const A12>(T.nq) * c).max(1e-300).inverse();
  const A12 k_half = ks * Eigen::Map<const A12>(T.w) * iG * iG.sqrt();
  // finish_blend's fields without its general case: κ rises monotonically to node 8 (see bounds
  // below), so the largest curvature is κ(8) and every table interval has Δκ ≥ 0, Δs > 0
  s.curvature = k_half[8];
  s.curvature_rate = ((k_half.segment<8>(1) - k_half.head<8>()) / piece).maxCoeff();
  s.full_length = s.table[16];
  nd.kappa_mid = k_half[8];
  const AN iGc = (Eigen::Map<const AN>(T.cp) + Eigen::Map<const AN>(T.cq) * c).max(1e-300).inverse(),
           igc = iGc.sqrt();
  nd.ta = Eigen::Map<const AN>(T.ca) * igc;
  nd.tb = Eigen::Map<const AN>(T.cb) * igc;
  nd.kappa = ks * Eigen::Map<const AN>(T.cw) * iGc * igc;
  nd.c = c;
  nd.inv_sin = 1.0 / sn;
}

// Exact per-axis bounds of |u_c| (U) and |κ n_c| (K) [1/mm] over the pieces of the symmetric line
// blend between the table nodes cuts_lines. The tangent turns monotonically by φ ∈ [0, θ] in the
// plane of u1 and u2 (B' is a positive combination of them whose ratio u²/(1 − u)² rises), and with
// N the tangent turned by +90° in that plane, dT/dφ = N and dN/dφ = −T. So per axis
// T_c = R_c·cos(φ − ψ_c) and N_c = −R_c·sin(φ − ψ_c), R_c the length of the axis' projection on the
// plane: over a piece (|Δφ| < π) |T_c| reaches R_c inside iff N_c changes sign, else its largest
// value is at an end; likewise |N_c| with T_c. κ rises monotonically up to node 8 and falls after it
// (u(1 − u)/g2^{3/2}: checked for cos θ over (−1, 1)), so on a piece that ends at or before node 8
// or starts at or after it κ is at most its larger end value, and |κ n_c| at most that times the
// largest |N_c|. In the plane T = ta·u1 + tb·u2 gives N = (−(tb + c·ta)·u1 + (ta + c·tb)·u2)/sin θ.
inline void bounds(const Nodes& nd, const Vec3& u1, const Vec3& u2, PieceArr (&U)[3], PieceArr (&K)[3]) {
  constexpr int n = n_cuts_lines;
  const AN na = -(nd.tb + nd.c * nd.ta) * nd.inv_sin, nb = (nd.ta + nd.c * nd.tb) * nd.inv_sin;
  PieceArr kmax = nd.kappa.head<n>().max(nd.kappa.segment<n>(1));
  for (int k = 0; k < n; ++k)  // a piece across the middle node has its largest κ there
    if (cuts_lines[k] < 8 && cuts_lines[k + 1] > 8) kmax[k] = nd.kappa_mid;
  kmax *= 1.0 + 1e-9;
  for (int c = 0; c < 3; ++c) {
    const AN t = nd.ta * u1[c] + nd.tb * u2[c], nn = na * u1[c] + nb * u2[c];
    const double r = std::sqrt(t[0] * t[0] + nn[0] * nn[0]);  // R_c (rotation leaves it unchanged)
    const PieceArr t0 = t.head<n>(), t1 = t.segment<n>(1), n0 = nn.head<n>(), n1 = nn.segment<n>(1);
    // "x changes sign over the piece" without select() (Eigen 3.4 does not vectorise it):
    // q = min(max(x0, x1), −min(x0, x1)) is positive exactly then, and min(r, 1e12·q) is r unless
    // |x| < 1e-12·r at an end, where the end value of the other component is within 1e-24·r of r
    const PieceArr qn = n0.max(n1).min(-n0.min(n1)), qt = t0.max(t1).min(-t0.min(t1));
    U[c] = (t0.abs().max(t1.abs()).max((1e12 * qn).min(r)) + 1e-12).min(1.0);
    K[c] = kmax * n0.abs().max(n1.abs()).max((1e12 * qt).min(r));
  }
}

}  // namespace

__attribute__((flatten)) int build(const LineBlendTables& T, Segment& whole, const Vec3& p0, const Vec3& vtx,
                                   const Vec3& p3, const Vec3& u1, const Vec3& u2, double d, long source,
                                   const Vec3& A, const Vec3& V, const Vec3& inv_acc, double vfeed, double v_prev,
                                   LineBlendRecord& r) {
  using Map = Eigen::Map<PieceArr>;
  Nodes nd;
  blend_lines(T, whole, p0, vtx, p3, u1, u2, d, source, nd);
  int np = n_cuts_lines;
  PieceArr U[3], K[3], ts, te;  // per axis bounds; trims of the whole blend
  bounds(nd, u1, u2, U, K);
  for (int k = 0; k < np; ++k) {
    ts[k] = whole.table[static_cast<std::size_t>(cuts_lines[k])];
    te[k] = whole.full_length - whole.table[static_cast<std::size_t>(cuts_lines[k + 1])];
  }
  {
    // a gentle turn: the centripetal part takes little of the budget at full speed; one piece whose
    // bounds are the largest of the pieces' (every lane holds it)
    double vcap = vfeed, kw = 0.0;
    for (int i = 0; i < 3; ++i) {
      vcap = std::min(vcap, V[i] / U[i].maxCoeff());  // U ≥ 1e-12
      kw = std::max(kw, K[i].maxCoeff());
    }
    if (kw * vcap * vcap <= 0.02 * A.minCoeff()) {
      np = 1;
      for (int i = 0; i < 3; ++i) {
        U[i].setConstant(U[i].maxCoeff());
        K[i].setConstant(K[i].maxCoeff());
      }
      ts.setZero();
      te.setZero();
    }
  }
  r.np = np;
  r.cursor = 0;
  // all pieces at once, per axis: the coefficients of the peak w = min_i (U_i·(vs² + ve²)/2 + L·A_i)/
  // (U_i + L·K_i), of the reach w = min_i (U_i·w0 + 2·L·A_i)/(U_i + 2·L·K_i) and of the tangential
  // budget, and the caps |u_i|·v ≤ V_i, K_i·v² ≤ A_i
  const PieceArr L = (whole.full_length - ts - te).max(0.0);
  // (the three reciprocals from one division: 1/U = e1·e2/(U·e1·e2), ...; U ≥ 1e-12, so no underflow)
  PieceArr vmax = PieceArr::Constant(vfeed), kr = PieceArr::Zero();  // kr = max_i K_i/A_i
  for (int i = 0; i < 3; ++i) {
    const PieceArr e1 = U[i] + L * K[i], e2 = U[i] + 2.0 * L * K[i];
    const PieceArr inv = (U[i] * e1 * e2).inverse();
    const PieceArr iu = e1 * e2 * inv, r1 = U[i] * e2 * inv, r2 = U[i] * e1 * inv;
    Map(r.iu[i]) = iu;
    Map(r.K[i]) = K[i];
    Map(r.p1[i]) = 0.5 * U[i] * r1;
    Map(r.p0[i]) = L * A[i] * r1;
    Map(r.alpha[i]) = U[i] * r2;
    Map(r.beta[i]) = 2.0 * L * A[i] * r2;
    vmax = vmax.min(V[i] * iu);
    kr = kr.max(K[i] * inv_acc[i]);
  }
  vmax = vmax.min(kr.inverse().sqrt());  // K_i·v² ≤ A_i (+inf where every K is 0)
  // the junction limit of piece k is the smaller cap of pieces k − 1 and k (piece 0: the cap before)
  PieceArr before;
  before[0] = v_prev;
  before.tail<n_cuts_lines - 1>() = vmax.head<n_cuts_lines - 1>();
  const PieceArr v_lim = before.min(vmax);
  Map(r.vmax) = vmax;
  Map(r.len) = L;
  Map(r.trim_s) = ts;
  Map(r.trim_e) = te;
  Map(r.w_junction) = v_lim * v_lim;
  Map(r.w_backward).setZero();
  return np;
}

// The pieces one after the other, as Planner::freeze_next() does for single nodes: each piece's end
// speed is the smaller of the backward speed of the next piece (of the next node: wt) and what it
// reaches from its start speed; its peak speed and tangential budget from the precomputed
// coefficients (no windows on blend pieces).
__attribute__((flatten)) double freeze(LineBlendRecord& r, double vs, double wt, const Vec3& A, double t_start) {
  using Arr = PieceArr;
  using Map = Eigen::Map<const Arr>;
  using Out = Eigen::Map<Arr>;
  constexpr int n = n_cuts_lines;
  const int np = r.np;
  // the chain of end speeds (sequential, in squared speeds: no root in the chain); unused lanes
  // repeat the last piece
  Arr WE;
  double w = vs * vs;
  for (int k = 0; k < np; ++k) {
    const double w_end = k + 1 < np ? r.w_backward[k + 1] : wt;
    const double reach = std::min({r.alpha[0][k] * w + r.beta[0][k], r.alpha[1][k] * w + r.beta[1][k],
                                   r.alpha[2][k] * w + r.beta[2][k]});
    w = std::min(w_end, reach);
    WE[k] = w;
  }
  for (int k = np; k < n; ++k) WE[k] = WE[np - 1];
  const Arr VE = WE.sqrt();
  Arr VS;  // piece k starts at the end speed of piece k − 1 (piece 0: the given speed)
  VS[0] = vs;
  VS.tail<n - 1>() = VE.head<n - 1>();
  // then all pieces at once: peak squared speed, tangential budget at that speed and the trapezoid
  // (Profile::make without windows, the same arithmetic lane by lane; written without select(),
  // which Eigen 3.4 does not vectorise)
  const Arr L = Map(r.len), S = VS * VS + VE * VE;
  const Arr vlow = VS.max(VE);
  Arr wp = Map(r.vmax) * Map(r.vmax);
  for (int i = 0; i < 3; ++i) wp = wp.min(Map(r.p1[i]) * S + Map(r.p0[i]));
  wp = wp.max((VS * VS).max(VE * VE));
  Arr a = Arr::Constant(inf);
  for (int i = 0; i < 3; ++i) a = a.min((A[i] - Map(r.K[i]) * wp) * Map(r.iu[i]));
  // a floor of 1e-6·A (as freeze_next: at the curvature cap the budget is 0); a stays finite since
  // every iu ≤ 1e12
  a = a.max(1e-6 * A.minCoeff());
  const Arr vmax = wp.sqrt();
  Arr vp = ((2.0 * a * L + S) / 2.0).max(0.0).sqrt();
  vp = vlow.max(vp.min(vmax.max(vlow)));
  // rounding (or the speed-dependent a chosen at the peak): make both ramps fit, a = need/(2L) where
  // that is larger (on a piece of length 0, L·1e300 = 0 keeps a)
  const Arr need = 2.0 * vp * vp - S;
  a = a.max((need / (2.0 * L).max(1e-300)).min(L * 1e300));
  const Arr ia = a.inverse();
  const Arr t1 = (vp - VS) * ia, d1 = 0.5 * (VS + vp) * t1;
  const Arr t3 = (vp - VE) * ia, d3 = 0.5 * (vp + VE) * t3;
  // the cruise takes what is left, so that the distances add up to the length exactly (all 0 when
  // vp = 0: then L = 0)
  Arr d2 = (L - d1 - d3).max(0.0);
  d2 = (d2 + (L - (d1 + d2 + d3))).max(0.0);
  const Arr t2 = d2 / vp.max(1e-300);
  const Arr dur = t1 + t2 + t3;
  Out(r.vs) = VS;
  Out(r.ve) = VE;
  Out(r.vp) = vp;
  Out(r.acc) = a;
  Out(r.t1) = t1;
  Out(r.t2) = t2;
  Out(r.t3) = t3;
  Out(r.d1) = d1;
  Out(r.d2) = d2;
  Out(r.d3) = d3;
  Out(r.dur) = dur;
  double t = t_start;
  for (int k = 0; k < np; ++k) {
    r.t0[k] = t;
    t += dur[k];
  }
  r.cursor = 0;
  return VE[np - 1];
}

extern const LineBlendKernels line_blend_kernel_table;
const LineBlendKernels line_blend_kernel_table{&build, &freeze, NETSHAPE_KERNEL_ISA_NAME};

}  // namespace netshape::motion::detail::NETSHAPE_KERNEL_ISA
#endif
