// The flat end mill's element loop, written once over simd::Batch<W> (W = 4 with AVX2 or AVX-512,
// 2 on the baseline, 1 without vector types) and compiled once per instruction set by
// netshape_add_kernels (kernels/flat_end_kernels.hpp). Branch free: the engagement test and the chip
// clamp are selects.
#include "core/simd.hpp"  // first: it wraps the intrinsic headers (see there)

#include <cmath>

#include "force/kernels/flat_end_kernels.hpp"
#include "netshape/core/types.hpp"

namespace netshape::force::kernels::NETSHAPE_KERNEL_ISA {
namespace {
using simd::Batch;

constexpr double two_pi = 2.0 * pi;
/// Lanes: at most the 4 partial sums of a step.
constexpr int kWidth = simd::native_width < 4 ? simd::native_width : 4;

constexpr int step_elements = 4;  // elements per step of the element loop (= number of partial sums)

/// Forces of W consecutive elements (pointers at the first), added to the partial sums (sx, sy, sz).
/// `valid` is 1 in the lanes that hold an element and 0 in the padding of the last step. Branch
/// free: the engagement test and the chip clamp are selects, and every lane does the operations of
/// the scalar model in the same order (only the order of the three sums over elements differs from
/// a one-element-at-a-time loop: partial sums, ~1e-16 relative).
template <int W, bool UseMap, bool KlineDevor>
NETSHAPE_SIMD_INLINE void element_step(const LoopConstants& L, const typename Batch<W>::D& thw,
                                       const typename Batch<W>::D& s0, const typename Batch<W>::D& c0,
                                       const double* off, const double* co, const double* so, const int* disk,
                                       const typename Batch<W>::D& valid, typename Batch<W>::D& sx,
                                       typename Batch<W>::D& sy, typename Batch<W>::D& sz) {
  using P = Batch<W>;
  using V = typename P::D;
  const V zero = P::set(0.0), tp = P::set(two_pi);
  V ph = thw + P::loadu(off);
  ph = ph >= tp ? ph - tp : ph;
  const V vco = P::loadu(co), vso = P::loadu(so);
  const V sp = s0 * vco + c0 * vso;  // sin φ
  const V cp = c0 * vco - s0 * vso;  // cos φ
  V w;
  if constexpr (UseMap) {
    const V fb = ph * P::set(L.bin_scale);
    double wl[W];
    for (int l = 0; l < W; ++l) {
      int b = static_cast<int>(P::lane(fb, l));
      b = b >= L.bins ? L.bins - 1 : b;
      wl[l] = L.mask[disk[l] * L.mask_stride + b] ? L.dz : 0.0;
    }
    w = P::loadu(wl);
  } else {
    V u = ph - P::set(L.st);
    u = u < zero ? u + tp : u;
    w = u <= P::set(L.span) ? P::set(L.dz) : zero;
  }
  w = valid != zero ? w : zero;
  if constexpr (!KlineDevor) {
    V h = P::set(L.c) * sp;  // chip thickness [mm]
    h = h > zero ? h : zero;
    const V ft = (P::set(L.k.ktc) * h + P::set(L.k.kte)) * w;
    const V fr = (P::set(L.k.krc) * h + P::set(L.k.kre)) * w;
    sx += -ft * cp - fr * sp;
    sy += ft * sp - fr * cp;
    sz += (P::set(L.k.kac) * h + P::set(L.k.kae)) * w;
  } else {
    // Cho & Suh eq. 1-5 in its own angle α = π − φ: t_c = f sin α, dF_T = K_T t_c D_z,
    // dF_R = K_R dF_T, Fx = Σ(−dF_R sin α + dF_T cos α), Fy = Σ(dF_R cos α + dF_T sin α).
    const V sa = sp, ca = -cp;
    V tc = P::set(L.c) * sa;
    tc = tc > zero ? tc : zero;
    const V dFT = P::set(L.KT) * tc * w;
    const V dFR = P::set(L.KR) * dFT;
    sx += -dFR * sa + dFT * ca;
    sy += dFR * ca + dFT * sa;
  }
}

/// The angle loop with packs of W lanes: for every angle, the element sum in steps of 4 elements
/// (4/W packs), the last step padded with inert lanes (valid = 0); the 4 partial sums of each
/// component are added as (s0 + s1) + (s2 + s3).
template <int W, bool UseMap, bool KlineDevor>
NETSHAPE_SIMD_INLINE void angle_loop_impl(const LoopConstants& L, const ElementArrays& A, const double* angles,
                                            Eigen::Index count, double* out, Eigen::Index out_stride) {
  using P = Batch<W>;
  using V = typename P::D;
  constexpr int S = step_elements, parts = S / W;
  const int n = L.n;
  const int full = n - n % S;
  // the padded last step: copies of the remaining elements, inert lanes behind them
  double toff[S], tco[S], tso[S], tvalid[S];
  int tdisk[S];
  for (int l = 0; l < S; ++l) {
    const bool in = full + l < n;
    toff[l] = in ? A.off[full + l] : 0.0;
    tco[l] = in ? A.co[full + l] : 1.0;
    tso[l] = in ? A.so[full + l] : 0.0;
    tdisk[l] = in ? A.disk[full + l] : 0;
    tvalid[l] = in ? 1.0 : 0.0;
  }
  const V all = P::set(1.0);
  for (Eigen::Index a = 0; a < count; ++a) {
    const double th = angles[a];
    const V thw = P::set(wrap_angle(th)), s0 = P::set(std::sin(th)), c0 = P::set(std::cos(th));
    V sx[parts], sy[parts], sz[parts];
    for (int p = 0; p < parts; ++p) sx[p] = sy[p] = sz[p] = P::set(0.0);
    for (int e = 0; e < full; e += S)
      for (int p = 0; p < parts; ++p) {
        const int i = e + p * W;
        element_step<W, UseMap, KlineDevor>(L, thw, s0, c0, A.off + i, A.co + i, A.so + i, A.disk + i, all,
                                            sx[p], sy[p], sz[p]);
      }
    if (full < n)
      for (int p = 0; p < parts; ++p) {
        const int i = p * W;
        const V valid = P::loadu(tvalid + i);
        element_step<W, UseMap, KlineDevor>(L, thw, s0, c0, toff + i, tco + i, tso + i, tdisk + i, valid,
                                            sx[p], sy[p], sz[p]);
      }
    double* o = out + a * out_stride;
    const V* sums[3] = {sx, sy, sz};
    for (int j = 0; j < 3; ++j) {
      double part[S];
      for (int p = 0; p < parts; ++p)
        for (int l = 0; l < W; ++l) part[p * W + l] = P::lane(sums[j][p], l);
      o[j] = (part[0] + part[1]) + (part[2] + part[3]);
    }
  }
}

template <bool UseMap, bool KlineDevor>
void loop(const LoopConstants& L, const ElementArrays& A, const double* angles, Eigen::Index count, double* out,
          Eigen::Index out_stride) {
  angle_loop_impl<kWidth, UseMap, KlineDevor>(L, A, angles, count, out, out_stride);
}
}  // namespace

extern const FlatEndKernels flat_end_kernels;
const FlatEndKernels flat_end_kernels{{{&loop<false, false>, &loop<false, true>}, {&loop<true, false>, &loop<true, true>}}};

}  // namespace netshape::force::kernels::NETSHAPE_KERNEL_ISA
