#include "netshape/force/flat_end_model.hpp"

#include <algorithm>
#include <cmath>

#include "netshape/core/error.hpp"
#include "netshape/cutter/cutter.hpp"

#if defined(__GNUC__) && !defined(__clang__)
#pragma GCC optimize("O3")  // the element loop is the hot path
#endif

// The element loop is written with GCC vector extensions (2 or 4 doubles per register), so it does
// not depend on the auto-vectoriser (GCC 12 does not vectorise this loop: "control flow in loop").
// On x86-64 an AVX2 version (4 lanes) is picked at run time when the CPU has AVX2, the baseline
// version (SSE2, 2 lanes) otherwise, so a portable wheel still uses AVX2. Other compilers get the
// same arithmetic one element at a time. Every version keeps 4 partial sums per force component
// (elements e ≡ 0, 1, 2, 3 mod 4) and adds them as (s0 + s1) + (s2 + s3), and none contracts to
// FMA, so all versions give bit-identical forces.
#if defined(__GNUC__) && !defined(__clang__)
#define NETSHAPE_FORCE_VECTORS 1
#define NETSHAPE_ALWAYS_INLINE inline __attribute__((always_inline))
#if defined(__x86_64__)
#define NETSHAPE_FORCE_AVX2 1
#endif
#else
#define NETSHAPE_ALWAYS_INLINE inline
#endif

namespace netshape::force {

namespace {
constexpr double two_pi = 2.0 * pi;
NETSHAPE_ALWAYS_INLINE double wrap(double a) { return a - two_pi * std::floor(a / two_pi); }

struct ElementArrays {
  const double* off;
  const double* co;
  const double* so;
  const int* disk;
};
struct LoopConstants {
  int n;
  double c, dz, st, span;
  LinearEdgeCoefficients k;
  double KT, KR;
  const std::uint8_t* mask;  // (disks, bins) with row stride mask_stride; null without map
  Eigen::Index mask_stride;
  int bins;
  double bin_scale;
};

/// Lane helpers for a pack of W doubles: a GCC vector (W = 2, 4) or a plain double (W = 1). Every
/// function taking or returning a pack is inlined (packs are passed by reference), so no vector
/// crosses a call boundary.
template <int W>
struct Pack;
template <>
struct Pack<1> {
  typedef double type;
  static NETSHAPE_ALWAYS_INLINE type load(const double* p) { return *p; }
  static NETSHAPE_ALWAYS_INLINE type splat(double x) { return x; }
  static NETSHAPE_ALWAYS_INLINE double lane(const type& v, int) { return v; }
};
#if defined(NETSHAPE_FORCE_VECTORS)
// Pack<4> returns 32-byte vectors from inlined helpers also in the baseline code (where they are
// never instantiated); the ABI note about passing AVX vectors does not apply to inlined calls.
#pragma GCC diagnostic ignored "-Wpsabi"
typedef double Double2 __attribute__((vector_size(16)));
typedef double Double4 __attribute__((vector_size(32)));
template <typename V>
struct VectorPack {
  typedef V type;
  static constexpr int width = sizeof(V) / sizeof(double);
  static NETSHAPE_ALWAYS_INLINE type load(const double* p) {
    type v;
    __builtin_memcpy(&v, p, sizeof v);
    return v;
  }
  static NETSHAPE_ALWAYS_INLINE type splat(double x) {
    type v;
    for (int l = 0; l < width; ++l) v[l] = x;
    return v;
  }
  static NETSHAPE_ALWAYS_INLINE double lane(const type& v, int l) { return v[l]; }
};
template <>
struct Pack<2> : VectorPack<Double2> {};
template <>
struct Pack<4> : VectorPack<Double4> {};
#endif
constexpr int step_elements = 4;  // elements per step of the element loop (= number of partial sums)

/// Forces of W consecutive elements (pointers at the first), added to the partial sums (sx, sy, sz).
/// `valid` is 1 in the lanes that hold an element and 0 in the padding of the last step. Branch
/// free: the engagement test and the chip clamp are selects, and every lane does the operations of
/// the scalar model in the same order (only the order of the three sums over elements differs from
/// a one-element-at-a-time loop: partial sums, ~1e-16 relative).
template <int W, bool UseMap, bool KlineDevor>
NETSHAPE_ALWAYS_INLINE void element_step(const LoopConstants& L, const typename Pack<W>::type& thw,
                                         const typename Pack<W>::type& s0, const typename Pack<W>::type& c0,
                                         const double* off, const double* co, const double* so, const int* disk,
                                         const typename Pack<W>::type& valid, typename Pack<W>::type& sx,
                                         typename Pack<W>::type& sy, typename Pack<W>::type& sz) {
  using P = Pack<W>;
  using V = typename P::type;
  const V zero = P::splat(0.0), tp = P::splat(two_pi);
  V ph = thw + P::load(off);
  ph = ph >= tp ? ph - tp : ph;
  const V vco = P::load(co), vso = P::load(so);
  const V sp = s0 * vco + c0 * vso;  // sin φ
  const V cp = c0 * vco - s0 * vso;  // cos φ
  V w;
  if constexpr (UseMap) {
    const V fb = ph * P::splat(L.bin_scale);
    double wl[W];
    for (int l = 0; l < W; ++l) {
      int b = static_cast<int>(P::lane(fb, l));
      b = b >= L.bins ? L.bins - 1 : b;
      wl[l] = L.mask[disk[l] * L.mask_stride + b] ? L.dz : 0.0;
    }
    w = P::load(wl);
  } else {
    V u = ph - P::splat(L.st);
    u = u < zero ? u + tp : u;
    w = u <= P::splat(L.span) ? P::splat(L.dz) : zero;
  }
  w = valid != zero ? w : zero;
  if constexpr (!KlineDevor) {
    V h = P::splat(L.c) * sp;  // chip thickness [mm]
    h = h > zero ? h : zero;
    const V ft = (P::splat(L.k.ktc) * h + P::splat(L.k.kte)) * w;
    const V fr = (P::splat(L.k.krc) * h + P::splat(L.k.kre)) * w;
    sx += -ft * cp - fr * sp;
    sy += ft * sp - fr * cp;
    sz += (P::splat(L.k.kac) * h + P::splat(L.k.kae)) * w;
  } else {
    // Cho & Suh eq. 1-5 in its own angle α = π − φ: t_c = f sin α, dF_T = K_T t_c D_z,
    // dF_R = K_R dF_T, Fx = Σ(−dF_R sin α + dF_T cos α), Fy = Σ(dF_R cos α + dF_T sin α).
    const V sa = sp, ca = -cp;
    V tc = P::splat(L.c) * sa;
    tc = tc > zero ? tc : zero;
    const V dFT = P::splat(L.KT) * tc * w;
    const V dFR = P::splat(L.KR) * dFT;
    sx += -dFR * sa + dFT * ca;
    sy += dFR * ca + dFT * sa;
  }
}

/// The angle loop with packs of W lanes: for every angle, the element sum in steps of 4 elements
/// (4/W packs), the last step padded with inert lanes (valid = 0); the 4 partial sums of each
/// component are added as (s0 + s1) + (s2 + s3).
template <int W, bool UseMap, bool KlineDevor>
NETSHAPE_ALWAYS_INLINE void angle_loop_impl(const LoopConstants& L, const ElementArrays& A, const double* angles,
                                            Eigen::Index count, double* out, Eigen::Index out_stride) {
  using P = Pack<W>;
  using V = typename P::type;
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
  const V all = P::splat(1.0);
  for (Eigen::Index a = 0; a < count; ++a) {
    const double th = angles[a];
    const V thw = P::splat(wrap(th)), s0 = P::splat(std::sin(th)), c0 = P::splat(std::cos(th));
    V sx[parts], sy[parts], sz[parts];
    for (int p = 0; p < parts; ++p) sx[p] = sy[p] = sz[p] = P::splat(0.0);
    for (int e = 0; e < full; e += S)
      for (int p = 0; p < parts; ++p) {
        const int i = e + p * W;
        element_step<W, UseMap, KlineDevor>(L, thw, s0, c0, A.off + i, A.co + i, A.so + i, A.disk + i, all,
                                            sx[p], sy[p], sz[p]);
      }
    if (full < n)
      for (int p = 0; p < parts; ++p) {
        const int i = p * W;
        const V valid = P::load(tvalid + i);
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

// One plain function per variant and ISA. The dispatcher below picks the AVX2 one when the CPU
// has AVX2 (GCC on x86-64), else the baseline vector one (GCC), else the scalar one.
#if defined(NETSHAPE_FORCE_VECTORS)
constexpr int base_lanes = 2;
#else
constexpr int base_lanes = 1;
#endif
using LoopFn = void (*)(const LoopConstants&, const ElementArrays&, const double*, Eigen::Index, double*,
                        Eigen::Index);
template <bool UseMap, bool KlineDevor>
void loop_base(const LoopConstants& L, const ElementArrays& A, const double* angles, Eigen::Index count,
               double* out, Eigen::Index out_stride) {
  angle_loop_impl<base_lanes, UseMap, KlineDevor>(L, A, angles, count, out, out_stride);
}
#if defined(NETSHAPE_FORCE_AVX2)
template <bool UseMap, bool KlineDevor>
__attribute__((target("avx2"))) void loop_avx2(const LoopConstants& L, const ElementArrays& A,
                                               const double* angles, Eigen::Index count, double* out,
                                               Eigen::Index out_stride) {
  angle_loop_impl<4, UseMap, KlineDevor>(L, A, angles, count, out, out_stride);
}
bool cpu_has_avx2() {
  static const bool yes = __builtin_cpu_supports("avx2");
  return yes;
}
#endif
template <bool UseMap, bool KlineDevor>
LoopFn pick_loop() {
#if defined(NETSHAPE_FORCE_AVX2)
  if (cpu_has_avx2()) return &loop_avx2<UseMap, KlineDevor>;
#endif
  return &loop_base<UseMap, KlineDevor>;
}
}  // namespace

void FlatEndModel::validate() const {
  NETSHAPE_CHECK_FINITE("radius", radius);
  NETSHAPE_CHECK(radius > 0.0, "radius", radius, "must be positive [mm]");
  cutter::check_flutes(flutes);
  NETSHAPE_CHECK_FINITE("helix", helix);
  NETSHAPE_CHECK(helix >= 0.0 && helix < deg2rad(85.0), "helix", helix, "must be in [0, 85°) [rad]");
  NETSHAPE_CHECK_FINITE("axial_depth", axial_depth);
  NETSHAPE_CHECK(axial_depth > 0.0, "axial_depth", axial_depth, "must be positive [mm]");
  NETSHAPE_CHECK_FINITE("feed_per_tooth", feed_per_tooth);
  NETSHAPE_CHECK(feed_per_tooth >= 0.0, "feed_per_tooth", feed_per_tooth, "must be ≥ 0 [mm]");
  NETSHAPE_CHECK_FINITE("disk_height", disk_height);
  NETSHAPE_CHECK(disk_height > 0.0, "disk_height", disk_height, "must be positive [mm]");
  NETSHAPE_CHECK(axial_depth / disk_height <= 1e6, "disk_height", disk_height,
                 "gives more than 1e6 disks over the axial depth");
  engagement.validate();
  if (coefficient_model == FlatCoefficientModel::linear_edge)
    linear_edge.validate();
  else
    kline_devor.validate();
}

int FlatEndModel::disks() const {
  return std::max(1, static_cast<int>(std::ceil(axial_depth / disk_height - 1e-9)));
}

double FlatEndModel::k_beta() const { return std::tan(helix) / radius; }

void FlatEndWorkspace::reset(const FlatEndModel& model) {
  model.validate();
  disks_ = model.disks();
  flutes_ = model.flutes;
  dz_ = model.axial_depth / disks_;
  radius_ = model.radius;
  helix_ = model.helix;
  depth_ = model.axial_depth;
  target_dz_ = model.disk_height;
  const int n = disks_ * flutes_;
  z_.resize(disks_);
  off_.resize(n);
  cos_off_.resize(n);
  sin_off_.resize(n);
  disk_of_.resize(n);
  const double kb = model.k_beta();
  for (int i = 0; i < disks_; ++i) {
    z_[i] = (i + 0.5) * dz_;
    for (int j = 0; j < flutes_; ++j) {
      const int e = i * flutes_ + j;
      const double o = j * two_pi / flutes_ - kb * z_[i];
      off_[e] = wrap(o);
      cos_off_[e] = std::cos(o);
      sin_off_[e] = std::sin(o);
      disk_of_[e] = i;
    }
  }
}

void flat_end_forces(const FlatEndModel& model, FlatEndWorkspace& ws, const Eigen::Ref<const VectorXd>& angles,
                     Eigen::Ref<Points3> out, const EngagementMap* map) {
  NETSHAPE_CHECK(out.rows() == angles.size(), "out.rows", out.rows(), "must equal the number of angles");
  if (ws.disks_ != model.disks() || ws.flutes_ != model.flutes || ws.radius_ != model.radius ||
      ws.helix_ != model.helix || ws.depth_ != model.axial_depth || ws.target_dz_ != model.disk_height)
    ws.reset(model);  // geometry changed: rebuild (allocates only then)
  else {
    model.engagement.validate();
    NETSHAPE_CHECK_FINITE("feed_per_tooth", model.feed_per_tooth);
    NETSHAPE_CHECK(model.feed_per_tooth >= 0.0, "feed_per_tooth", model.feed_per_tooth, "must be ≥ 0 [mm]");
    if (model.coefficient_model == FlatCoefficientModel::linear_edge)
      model.linear_edge.validate();
    else
      model.kline_devor.validate();
  }
  if (map) {
    NETSHAPE_CHECK(map->disks() == ws.disks_, "engagement_map.rows", map->disks(),
                   "must equal the number of disks of the model");
    NETSHAPE_CHECK(map->bins() >= 4, "engagement_map.cols", map->bins(), "must be at least 4 bins");
  }
  for (Eigen::Index k = 0; k < angles.size(); ++k)
    NETSHAPE_CHECK_FINITE("angles", angles[k]);

  const int n = ws.elements();
  const double c = model.feed_per_tooth;
  const double dz = ws.dz_;
  const double st = model.engagement.phi_st;
  const double span = model.engagement.phi_ex - model.engagement.phi_st;
  const bool kd = model.coefficient_model == FlatCoefficientModel::kline_devor;
  const LinearEdgeCoefficients k = model.linear_edge;
  const double KT = model.kline_devor.kt, KR = model.kline_devor.kr;
  const int bins = map ? map->bins() : 0;
  const double bin_scale = map ? bins / two_pi : 0.0;

  const ElementArrays arr{ws.off_.data(), ws.cos_off_.data(), ws.sin_off_.data(), ws.disk_of_.data()};
  const LoopConstants lc{n,    c,  dz, st, span, k, KT, KR, map ? map->mask.data() : nullptr,
                         map ? static_cast<Eigen::Index>(map->mask.outerStride()) : 0,
                         bins, bin_scale};
  const double* th = angles.data();
  const Eigen::Index count = angles.size();
  double* o = out.data();
  const Eigen::Index os = out.outerStride();
  const LoopFn loop = map ? (kd ? pick_loop<true, true>() : pick_loop<true, false>())
                          : (kd ? pick_loop<false, true>() : pick_loop<false, false>());
  loop(lc, arr, th, count, o, os);
}

Points3 flat_end_forces(const FlatEndModel& model, const Eigen::Ref<const VectorXd>& angles) {
  FlatEndWorkspace ws(model);
  Points3 out(angles.size(), 3);
  flat_end_forces(model, ws, angles, out);
  return out;
}

Points3 flat_end_forces(const FlatEndModel& model, const Eigen::Ref<const VectorXd>& angles,
                        const EngagementMap& map) {
  FlatEndWorkspace ws(model);
  Points3 out(angles.size(), 3);
  flat_end_forces(model, ws, angles, out, &map);
  return out;
}

VectorXd rotation_angles(int count, double revolutions) {
  NETSHAPE_CHECK(count >= 1, "count", count, "must be at least 1");
  NETSHAPE_CHECK_FINITE("revolutions", revolutions);
  NETSHAPE_CHECK(revolutions > 0.0, "revolutions", revolutions, "must be positive");
  VectorXd a(count);
  for (int k = 0; k < count; ++k) a[k] = two_pi * revolutions * k / count;
  return a;
}

}  // namespace netshape::force

namespace netshape::force {

void flat_end_moments(const FlatEndModel& model, FlatEndWorkspace& ws, const Eigen::Ref<const VectorXd>& angles,
                      Eigen::Ref<MatrixXdR> out) {
  NETSHAPE_CHECK(out.rows() == angles.size() && out.cols() == 6, "out.rows", out.rows(),
                 "must be (number of angles, 6)");
  ws.reset(model);
  for (Eigen::Index k = 0; k < angles.size(); ++k) NETSHAPE_CHECK_FINITE("angles", angles[k]);
  const int n = ws.elements();
  const double c = model.feed_per_tooth, dz = ws.dz_;
  const double st = model.engagement.phi_st;
  const double span = model.engagement.phi_ex - model.engagement.phi_st;
  for (Eigen::Index a = 0; a < angles.size(); ++a) {
    const double th = angles[a];
    const double thw = wrap(th);
    const double s0 = std::sin(th), c0 = std::cos(th);
    double m0 = 0, m1 = 0, m2 = 0, m3 = 0, m4 = 0, m5 = 0;
    for (int e = 0; e < n; ++e) {
      double ph = thw + ws.off_[e];
      ph = ph >= two_pi ? ph - two_pi : ph;
      double u = ph - st;
      u = u < 0.0 ? u + two_pi : u;
      if (u > span) continue;
      const double sp = s0 * ws.cos_off_[e] + c0 * ws.sin_off_[e];
      const double cp = c0 * ws.cos_off_[e] - s0 * ws.sin_off_[e];
      const double h = std::max(c * sp, 0.0);
      m0 += h * cp;
      m1 += h * sp;
      m2 += h;
      m3 += cp;
      m4 += sp;
      m5 += 1.0;
    }
    out(a, 0) = m0 * dz;
    out(a, 1) = m1 * dz;
    out(a, 2) = m2 * dz;
    out(a, 3) = m3 * dz;
    out(a, 4) = m4 * dz;
    out(a, 5) = m5 * dz;
  }
}

}  // namespace netshape::force
