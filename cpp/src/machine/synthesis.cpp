// Error synthesis along the two chains of a machine: exact product of homogeneous transforms and
// its first-order expansion (seeds/003 eq. 9-11 generalised). The exact path tracks the deviation
// d = W - W_nominal directly, using R - I computed without cancellation, so small errors keep full
// relative precision.
#include "netshape/machine/synthesis.hpp"

#include <algorithm>
#include <cmath>

#include "netshape/core/error.hpp"

namespace netshape::machine {

namespace {

/// sin x and cos x - 1, exact to rounding, without cancellation for small x.
inline void sincos_m1(double x, double& s, double& cm) noexcept {
  const double ax = std::abs(x);
  if (ax < 1e-3) {
    // geometric errors are almost always this small: three terms are exact to rounding here
    // (the first omitted terms are below 1e-21 relative)
    const double x2 = x * x;
    constexpr double k6 = 1.0 / 6.0, k20 = 1.0 / 20.0, k12 = 1.0 / 12.0, k30 = 1.0 / 30.0;
    s = x * (1.0 - x2 * k6 * (1.0 - x2 * k20));
    cm = -0.5 * x2 * (1.0 - x2 * k12 * (1.0 - x2 * k30));
  } else if (ax < 0.05) {
    const double x2 = x * x;
    // Taylor series to x^9 / x^10: the next terms are below 1e-21 relative for |x| < 0.05
    constexpr double k6 = 1.0 / 6.0, k20 = 1.0 / 20.0, k42 = 1.0 / 42.0, k72 = 1.0 / 72.0;
    constexpr double k12 = 1.0 / 12.0, k30 = 1.0 / 30.0, k56 = 1.0 / 56.0, k90 = 1.0 / 90.0;
    s = x * (1.0 - x2 * k6 * (1.0 - x2 * k20 * (1.0 - x2 * k42 * (1.0 - x2 * k72))));
    cm = -0.5 * x2 * (1.0 - x2 * k12 * (1.0 - x2 * k30 * (1.0 - x2 * k56 * (1.0 - x2 * k90))));
  } else {
    s = std::sin(x);
    const double h = std::sin(0.5 * x);
    cm = -2.0 * h * h;
  }
}

/// R(a, b, c) - I with R = Rz(c) Ry(b) Rx(a).
inline Mat3 rotation_minus_identity(double a, double b, double c) noexcept {
  double sa, cma, sb, cmb, sc, cmc;
  sincos_m1(a, sa, cma);
  sincos_m1(b, sb, cmb);
  sincos_m1(c, sc, cmc);
  const double ca = 1.0 + cma, cb = 1.0 + cmb, cc = 1.0 + cmc;
  Mat3 m;
  m(0, 0) = cmb + cmc + cmb * cmc;
  m(0, 1) = sa * sb * cc - ca * sc;
  m(0, 2) = ca * sb * cc + sa * sc;
  m(1, 0) = cb * sc;
  m(1, 1) = sa * sb * sc + cma + cmc + cma * cmc;
  m(1, 2) = ca * sb * sc - sa * cc;
  m(2, 0) = -sb;
  m(2, 1) = sa * cb;
  m(2, 2) = cma + cmb + cma * cmb;
  return m;
}

/// Rx(a) Ry(b) - I (spindle tilt).
inline Mat3 tilt_minus_identity(double a, double b) noexcept {
  double sa, cma, sb, cmb;
  sincos_m1(a, sa, cma);
  sincos_m1(b, sb, cmb);
  const double ca = 1.0 + cma, cb = 1.0 + cmb;
  // Rx(a) Ry(b) = [[cb, 0, sb], [sa sb, ca, -sa cb], [-ca sb, sa, ca cb]]
  Mat3 m;
  m << cmb, 0.0, sb, sa * sb, cma, -sa * cb, -ca * sb, sa, cma + cmb + cma * cmb;
  return m;
}

inline Vec3 unit(int k) { return Vec3::Unit(k); }

}  // namespace

Mat3 rotation_zyx(double a, double b, double c) noexcept {
  return Mat3::Identity() + rotation_minus_identity(a, b, c);
}

namespace {
// Evaluation of a prepared error function, kept in this translation unit so it inlines into the
// synthesis loop (a call through the PLT of the shared module costs more than the arithmetic).
inline double eval_prepared(const detail::PreparedFunction& f, double q) {
  const auto kind = f.kind;
  const int n = f.n;
  const double* c = f.c;
  const double* x = f.x;
  const double lo = f.lo, hi = f.hi;
  switch (kind) {
    case ErrorFunction::Kind::zero:
      return 0.0;
    case ErrorFunction::Kind::polynomial: {
      double r = c[n - 1];
      for (int j = n - 2; j >= 0; --j) r = r * q + c[j];
      return r;
    }
    case ErrorFunction::Kind::table: {
      int i;
      if (!(q >= lo && q <= hi)) {
        if (f.out_of_range == OutOfRange::error || !std::isfinite(q)) return (*f.source)(q);  // throws
        if (f.out_of_range == OutOfRange::clamp) return q < lo ? c[0] : c[n - 1];
        i = q < lo ? 0 : n - 2;
      } else if (f.uniform) {
        const double u = (q - lo) * f.inv_step;  // no division on the fast path
        i = static_cast<int>(u);
        if (i > n - 2) i = n - 2;
        const double t = u - i;
        return c[i] + t * (c[i + 1] - c[i]);
      } else {
        i = static_cast<int>(std::upper_bound(x, x + n, q) - x) - 1;
        if (i > n - 2) i = n - 2;
        if (i < 0) i = 0;
      }
      const double t = (q - x[i]) / (x[i + 1] - x[i]);
      return c[i] + t * (c[i + 1] - c[i]);
    }
  }
  return 0.0;
}
// Value and slope de/dq (tables: slope of the segment; clamped outside: 0).
inline double eval_prepared_slope(const detail::PreparedFunction& f, double q, double& slope) {
  switch (f.kind) {
    case ErrorFunction::Kind::zero:
      slope = 0.0;
      return 0.0;
    case ErrorFunction::Kind::polynomial: {
      const double* c = f.c;
      double r = c[f.n - 1], d = 0.0;
      for (int j = f.n - 2; j >= 0; --j) {
        d = d * q + r;
        r = r * q + c[j];
      }
      slope = d;
      return r;
    }
    case ErrorFunction::Kind::table: {
      const int n = f.n;
      const double* x = f.x;
      const double* c = f.c;
      int i;
      if (!(q >= f.lo && q <= f.hi)) {
        if (f.out_of_range == OutOfRange::clamp && std::isfinite(q)) {
          slope = 0.0;
          return q < f.lo ? c[0] : c[n - 1];
        }
        if (f.out_of_range == OutOfRange::error || !std::isfinite(q)) return (*f.source)(q);  // throws
        i = q < f.lo ? 0 : n - 2;
      } else if (f.uniform) {
        const double u = (q - f.lo) * f.inv_step;
        i = static_cast<int>(u);
        if (i > n - 2) i = n - 2;
        slope = (c[i + 1] - c[i]) * f.inv_step;
        return c[i] + (u - i) * (c[i + 1] - c[i]);
      } else {
        i = static_cast<int>(std::upper_bound(x, x + n, q) - x) - 1;
        if (i > n - 2) i = n - 2;
        if (i < 0) i = 0;
      }
      slope = (c[i + 1] - c[i]) / (x[i + 1] - x[i]);
      return c[i] + (q - x[i]) * slope;
    }
  }
  slope = 0.0;
  return 0.0;
}
}  // namespace

double detail::PreparedFunction::operator()(double q) const { return eval_prepared(*this, q); }


namespace {
// Pack the six components of axis k for one-pass evaluation when they allow it.
void prepare_kernel(const Machine& machine, int k, detail::AxisKernel& ker) {
  const auto& errs = machine.axes[k].errors;
  bool any_table = false, any_poly = false;
  const ErrorFunction* first_table = nullptr;
  for (const ErrorFunction& f : errs) {
    if (f.kind == ErrorFunction::Kind::polynomial && !f.coefficients.empty()) any_poly = true;
    if (f.kind == ErrorFunction::Kind::table) {
      any_table = true;
      if (!first_table) first_table = &f;
    }
  }
  ker = detail::AxisKernel{};
  if (!any_table) {
    ker.mode = detail::AxisKernel::Mode::polynomial;
    int terms = 1;
    for (const ErrorFunction& f : errs)
      if (f.kind == ErrorFunction::Kind::polynomial) terms = std::max(terms, static_cast<int>(f.coefficients.size()));
    ker.terms = terms;
    ker.packed.assign(static_cast<std::size_t>(terms) * 6, 0.0);
    for (int c = 0; c < 6; ++c)
      if (errs[c].kind == ErrorFunction::Kind::polynomial)
        for (std::size_t j = 0; j < errs[c].coefficients.size(); ++j) ker.packed[j * 6 + c] = errs[c].coefficients[j];
    return;
  }
  if (any_poly) return;  // mixed polynomials and tables: per-function evaluation
  for (const ErrorFunction& f : errs) {
    if (f.kind != ErrorFunction::Kind::table) continue;
    if (f.positions != first_table->positions || f.out_of_range != first_table->out_of_range) return;
  }
  // all tables on the same positions (zero components become zero columns): one lookup per axis
  const int n = static_cast<int>(first_table->positions.size());
  ker.mode = detail::AxisKernel::Mode::table;
  ker.terms = n;
  ker.packed.assign(static_cast<std::size_t>(n) * 6, 0.0);
  for (int c = 0; c < 6; ++c)
    if (errs[c].kind == ErrorFunction::Kind::table)
      for (int i = 0; i < n; ++i) ker.packed[static_cast<std::size_t>(i) * 6 + c] = errs[c].values[i];
  ker.x = first_table->positions.data();
  ker.lo = first_table->positions.front();
  ker.hi = first_table->positions.back();
  const double step = (ker.hi - ker.lo) / (n - 1);
  ker.inv_step = 1.0 / step;
  ker.uniform = true;
  for (int i = 0; i < n; ++i)
    if (std::abs(first_table->positions[i] - (ker.lo + i * step)) > 1e-9 * (1.0 + std::abs(ker.hi - ker.lo)))
      ker.uniform = false;
  ker.out_of_range = first_table->out_of_range;
  ker.source = first_table;
}
}  // namespace

MachineData::MachineData(const Machine& machine) {
  machine.validate();
  for (int k = 0; k < 3; ++k) {
    for (int j = 0; j < 6; ++j) {
      const ErrorFunction& f = machine.axes[k].errors[j];
      detail::PreparedFunction& pf = functions[k * 6 + j];
      pf.source = &f;
      pf.kind = f.kind;
      pf.out_of_range = f.out_of_range;
      if (f.kind == ErrorFunction::Kind::polynomial) {
        if (f.coefficients.empty()) {
          pf.kind = ErrorFunction::Kind::zero;
        } else {
          pf.n = static_cast<int>(f.coefficients.size());
          pf.c = f.coefficients.data();
        }
      } else if (f.kind == ErrorFunction::Kind::table) {
        pf.n = static_cast<int>(f.positions.size());
        pf.c = f.values.data();
        pf.x = f.positions.data();
        pf.lo = f.positions.front();
        pf.hi = f.positions.back();
        const double step = (pf.hi - pf.lo) / (pf.n - 1);
        pf.inv_step = 1.0 / step;
        pf.uniform = true;
        for (int i = 0; i < pf.n; ++i)
          if (std::abs(f.positions[i] - (pf.lo + i * step)) > 1e-9 * (1.0 + std::abs(pf.hi - pf.lo))) pf.uniform = false;
      }
    }
    prepare_kernel(machine, k, kernels[k]);
  }
  all_polynomial = true;
  lane_terms = 1;
  for (int k = 0; k < 3; ++k) {
    if (kernels[k].mode != detail::AxisKernel::Mode::polynomial) all_polynomial = false;
    lane_terms = std::max(lane_terms, kernels[k].terms);
  }
  if (all_polynomial) {
    lane_coefficients.assign(static_cast<std::size_t>(lane_terms) * 18, 0.0);
    for (int k = 0; k < 3; ++k)
      for (int j = 0; j < kernels[k].terms; ++j)
        for (int c = 0; c < 6; ++c) {
          const int lane = c < 3 ? 9 + 3 * k + c : 3 * k + (c - 3);
          lane_coefficients[static_cast<std::size_t>(j) * 18 + lane] = kernels[k].packed[j * 6 + c];
        }
  }
  // Chains in evaluation order, and which Abbe arms grow with which axis (first-order Jacobian).
  tool_steps = 0;
  int ns = 0;
  for (auto it = machine.tool_chain.rbegin(); it != machine.tool_chain.rend(); ++it, ++ns, ++tool_steps)
    steps[ns] = detail::ChainStep{*it, true, machine.axes[*it].origin};
  for (int k : machine.workpiece_chain) steps[ns++] = detail::ChainStep{k, false, machine.axes[k].origin};
  std::array<int, 3> tool_pos{-1, -1, -1}, work_pos{-1, -1, -1};
  for (std::size_t i = 0; i < machine.tool_chain.size(); ++i) tool_pos[machine.tool_chain[i]] = static_cast<int>(i);
  for (std::size_t i = 0; i < machine.workpiece_chain.size(); ++i)
    work_pos[machine.workpiece_chain[i]] = static_cast<int>(i);
  for (int k = 0; k < 3; ++k)
    for (int j = 0; j < 3; ++j)
      arm_grows[k][j] = tool_pos[k] >= 0 ? (tool_pos[j] >= 0 ? tool_pos[j] < tool_pos[k] : true)
                                         : (work_pos[j] >= 0 && work_pos[j] >= work_pos[k]);
  // Squareness: X is the reference; Y = Rz(EC0Y) ŷ; Z = Rx(EA0Z) Ry(EB0Z) ẑ. Stored as deviations
  // from the nominal unit vector (exact), direction_linear as first-order deviations.
  double s, cm;
  direction[0] = Vec3::Zero();
  direction_linear[0] = Vec3::Zero();
  sincos_m1(machine.ec0y, s, cm);
  direction[1] = Vec3(-s, cm, 0.0);
  direction_linear[1] = Vec3(-machine.ec0y, 0.0, 0.0);
  direction[2] = tilt_minus_identity(machine.ea0z, machine.eb0z).col(2);  // Rx(a) Ry(b) ẑ - ẑ
  direction_linear[2] = Vec3(machine.eb0z, -machine.ea0z, 0.0);
  tip_nominal = machine.nominal_tip();
  const Vec3 tilt_dev =
      machine.tool_length * (tilt_minus_identity(machine.spindle_tilt_a, machine.spindle_tilt_b) *
                             machine.tool_direction);
  tip_local = tilt_dev;  // deviation of the tilted tip from the nominal tip [mm]
  tip_local_linear =
      machine.tool_length * Vec3(machine.spindle_tilt_a, machine.spindle_tilt_b, 0.0).cross(machine.tool_direction);
  for (int k = 0; k < 3; ++k) {
    delta[k].setZero();
    epsilon[k].setZero();
    delta_slope[k].setZero();
    epsilon_slope[k].setZero();
  }
}

namespace {
// The six components of axis k at q into e[6] (and their slopes into s[6] when Slope).
template <bool Slope>
inline void evaluate_axis(const MachineData& data, int k, double q, double* e, double* s) {
  const detail::AxisKernel& ker = data.kernels[k];
  switch (ker.mode) {
    case detail::AxisKernel::Mode::polynomial: {
      const double* c = ker.packed.data();
      const int last = ker.terms - 1;
      for (int i = 0; i < 6; ++i) e[i] = c[last * 6 + i];
      if (Slope)
        for (int i = 0; i < 6; ++i) s[i] = 0.0;
      for (int j = last - 1; j >= 0; --j) {
        for (int i = 0; i < 6; ++i) {
          if (Slope) s[i] = s[i] * q + e[i];
          e[i] = e[i] * q + c[j * 6 + i];
        }
      }
      return;
    }
    case detail::AxisKernel::Mode::table: {
      const int n = ker.terms;
      const double* v = ker.packed.data();
      int i;
      double t, inv_dx;
      if (!(q >= ker.lo && q <= ker.hi)) {
        if (ker.out_of_range == OutOfRange::error || !std::isfinite(q)) {
          (*ker.source)(q);  // throws the table's message
        }
        if (ker.out_of_range == OutOfRange::clamp) {
          const double* row = q < ker.lo ? v : v + static_cast<std::ptrdiff_t>(n - 1) * 6;
          for (int c = 0; c < 6; ++c) e[c] = row[c];
          if (Slope)
            for (int c = 0; c < 6; ++c) s[c] = 0.0;
          return;
        }
        i = q < ker.lo ? 0 : n - 2;
        inv_dx = 1.0 / (ker.x[i + 1] - ker.x[i]);
        t = (q - ker.x[i]) * inv_dx;
      } else if (ker.uniform) {
        const double u = (q - ker.lo) * ker.inv_step;
        i = static_cast<int>(u);
        if (i > n - 2) i = n - 2;
        t = u - i;
        inv_dx = ker.inv_step;
      } else {
        i = static_cast<int>(std::upper_bound(ker.x, ker.x + n, q) - ker.x) - 1;
        if (i > n - 2) i = n - 2;
        if (i < 0) i = 0;
        inv_dx = 1.0 / (ker.x[i + 1] - ker.x[i]);
        t = (q - ker.x[i]) * inv_dx;
      }
      const double* a = v + static_cast<std::ptrdiff_t>(i) * 6;
      const double* b = a + 6;
      for (int c = 0; c < 6; ++c) {
        const double dv = b[c] - a[c];
        e[c] = a[c] + t * dv;
        if (Slope) s[c] = dv * inv_dx;
      }
      return;
    }
    case detail::AxisKernel::Mode::generic:
    default: {
      const detail::PreparedFunction* f = &data.functions[k * 6];
      for (int c = 0; c < 6; ++c) {
        if (Slope)
          e[c] = eval_prepared_slope(f[c], q, s[c]);
        else
          e[c] = eval_prepared(f[c], q);
      }
      return;
    }
  }
}

using Lanes = Eigen::Array<double, 18, 1>;
using Lanes10 = Eigen::Array<double, 10, 1>;

// All 18 components at p into lanes (see MachineData::lane_coefficients), with slopes when Slope.
template <bool Slope>
inline void evaluate_lanes(const MachineData& data, const Vec3& p, Lanes& e, Lanes& s) {
  if (data.all_polynomial) {
    Lanes q;
    for (int k = 0; k < 3; ++k) {
      q.segment<3>(3 * k).setConstant(p[k]);
      q.segment<3>(9 + 3 * k).setConstant(p[k]);
    }
    const double* c = data.lane_coefficients.data();
    const int last = data.lane_terms - 1;
    e = Eigen::Map<const Lanes>(c + last * 18);
    if (Slope) s.setZero();
    for (int j = last - 1; j >= 0; --j) {
      if (Slope) s = s * q + e;
      e = e * q + Eigen::Map<const Lanes>(c + j * 18);
    }
    return;
  }
  for (int k = 0; k < 3; ++k) {
    double v[6], d[6];
    evaluate_axis<Slope>(data, k, p[k], v, d);
    for (int c = 0; c < 3; ++c) {
      e[9 + 3 * k + c] = v[c];
      e[3 * k + c] = v[3 + c];
      if (Slope) {
        s[9 + 3 * k + c] = d[c];
        s[3 * k + c] = d[3 + c];
      }
    }
  }
}

// sin and cos − 1 of the nine angles (lanes 0..8; lane 9 is computed and ignored): short Taylor
// series, exact to rounding, when every |angle| < 1e-3 (omitted terms below 1e-21 relative).
EIGEN_STRONG_INLINE void sincos_lanes(const Lanes& e, Lanes10& s, Lanes10& cm) noexcept {
  const Lanes10 x = e.head<10>();
  const Lanes10 x2 = x * x;
  if (x2.head<9>().maxCoeff() < 1e-6) {
    constexpr double k6 = -1.0 / 6.0, k120 = 1.0 / 120.0, k24 = 1.0 / 24.0, k720 = -1.0 / 720.0;
    s = x + x * x2 * (k6 + x2 * k120);
    cm = x2 * (-0.5 + x2 * (k24 + x2 * k720));
  } else {
    for (int i = 0; i < 9; ++i) sincos_m1(x[i], s[i], cm[i]);
  }
}

// Exact tip error; with Jacobian, also the first-order Jacobian (column k = δ'_k + s_k + ε'_k × r_k +
// (Σ_{j: arm grows with q_k} ε_j) × u_k). The part of each step that does not depend on the running
// deviation d is formed first, so that the dependent chain is one 3×3 product per axis.
template <bool Jacobian>
inline Vec3 exact_kernel(MachineData& data, const Vec3& p, Mat3* jacobian) {
  Lanes e, sl;
  evaluate_lanes<Jacobian>(data, p, e, sl);
  Lanes10 s, cm;
  sincos_lanes(e, s, cm);
  // Plain scalars (the 3-vectors do not fill SIMD registers; this keeps them in registers).
  double v0 = data.tip_nominal[0], v1 = data.tip_nominal[1], v2 = data.tip_nominal[2];
  double d0 = data.tip_local[0], d1 = data.tip_local[1], d2 = data.tip_local[2];
  std::array<Vec3, 3> arm;
  for (int i = 0; i < 3; ++i) {
    const detail::ChainStep& st = data.steps[i];
    const int k = st.axis;
    const double q = p[k];
    // R − I from sin and cos − 1 of (a, b, c), R = Rz(c)·Ry(b)·Rx(a) (no cancellation)
    const double sa = s[3 * k], sb = s[3 * k + 1], sc = s[3 * k + 2];
    const double cma = cm[3 * k], cmb = cm[3 * k + 1], cmc = cm[3 * k + 2];
    const double ca = 1.0 + cma, cb = 1.0 + cmb, cc = 1.0 + cmc;
    const double sasb = sa * sb, casb = ca * sb;
    const double m00 = cmb + cmc + cmb * cmc, m01 = sasb * cc - ca * sc, m02 = casb * cc + sa * sc;
    const double m10 = cb * sc, m11 = sasb * sc + cma + cmc + cma * cmc, m12 = casb * sc - sa * cc;
    const double m20 = -sb, m21 = sa * cb, m22 = cma + cmb + cma * cmb;
    // t − q u = q (u' − u) + δ
    const Vec3& du = data.direction[k];
    const double t0 = q * du[0] + e[9 + 3 * k], t1 = q * du[1] + e[10 + 3 * k], t2 = q * du[2] + e[11 + 3 * k];
    const double o0 = st.origin[0] + (k == 0 ? q : 0.0), o1 = st.origin[1] + (k == 1 ? q : 0.0),
                 o2 = st.origin[2] + (k == 2 ? q : 0.0);  // origin + q u
    double c0, c1, c2;
    if (st.tool) {
      // v_frame = o + R (v + d) + q u' + δ ; nominal o + v + q u. The part that does not depend on d is
      // formed first, so that the chain of dependent operations is one 3×3 product per axis.
      if (Jacobian) arm[k] = Vec3(v0, v1, v2);
      c0 = m00 * v0 + m01 * v1 + m02 * v2 + t0;
      c1 = m10 * v0 + m11 * v1 + m12 * v2 + t1;
      c2 = m20 * v0 + m21 * v1 + m22 * v2 + t2;
      v0 += o0, v1 += o1, v2 += o2;
    } else {
      // The table moves by −t = −(q u' + δ) and turns by R⁻¹ about its own origin:
      // W = R (v + d − o + t) ; nominal v − o + q u (arm: the point relative to the carriage's current origin).
      v0 -= st.origin[0], v1 -= st.origin[1], v2 -= st.origin[2];
      if (k == 0) v0 += q;
      if (k == 1) v1 += q;
      if (k == 2) v2 += q;
      if (Jacobian) arm[k] = Vec3(v0, v1, v2);
      const double w0 = v0 + t0, w1 = v1 + t1, w2 = v2 + t2;
      c0 = t0 + (m00 * w0 + m01 * w1 + m02 * w2);
      c1 = t1 + (m10 * w0 + m11 * w1 + m12 * w2);
      c2 = t2 + (m20 * w0 + m21 * w1 + m22 * w2);
    }
    const double n0 = d0 + (m00 * d0 + m01 * d1 + m02 * d2 + c0);
    const double n1 = d1 + (m10 * d0 + m11 * d1 + m12 * d2 + c1);
    const double n2 = d2 + (m20 * d0 + m21 * d1 + m22 * d2 + c2);
    d0 = n0, d1 = n1, d2 = n2;
  }
  if (Jacobian) {
    for (int k = 0; k < 3; ++k) {
      data.delta[k] = e.segment<3>(9 + 3 * k).matrix();
      data.epsilon[k] = e.segment<3>(3 * k).matrix();
      data.delta_slope[k] = sl.segment<3>(9 + 3 * k).matrix();
      data.epsilon_slope[k] = sl.segment<3>(3 * k).matrix();
    }
    for (int k = 0; k < 3; ++k) {
      Vec3 eps_sum = Vec3::Zero();
      for (int j = 0; j < 3; ++j)
        if (data.arm_grows[k][j]) eps_sum += data.epsilon[j];
      jacobian->col(k) = data.delta_slope[k] + data.direction_linear[k] + data.epsilon_slope[k].cross(arm[k]) +
                         eps_sum.cross(Vec3::Unit(k));
    }
  }
  return Vec3(d0, d1, d2);
}

inline void evaluate_components_inline(MachineData& data, const Vec3& p) {
  for (int k = 0; k < 3; ++k) {
    double e[6];
    evaluate_axis<false>(data, k, p[k], e, nullptr);
    data.delta[k] = Vec3(e[0], e[1], e[2]);
    data.epsilon[k] = Vec3(e[3], e[4], e[5]);
  }
}

}  // namespace

void evaluate_components(const Machine& machine, MachineData& data, const Vec3& p) {
  (void)machine;
  evaluate_components_inline(data, p);
}

Vec3 tip_error(const Machine& machine, MachineData& data, const Vec3& p, Order order) {
  if (order == Order::exact) return exact_kernel<false>(data, p, nullptr);
  evaluate_components_inline(data, p);
  // First order: e₁ = Σ_k [δ_k + q_k (u'_k − u_k)₁ + ε_k × r_k] + L (θ × d).
  Vec3 v = data.tip_nominal;
  Vec3 d = data.tip_local_linear;
  const auto& tc = machine.tool_chain;
  for (auto it = tc.rbegin(); it != tc.rend(); ++it) {
    const int k = *it;
    const double q = p[k];
    d = d + data.epsilon[k].cross(v) + q * data.direction_linear[k] + data.delta[k];
    v = machine.axes[k].origin + v + q * unit(k);
  }
  for (int k : machine.workpiece_chain) {
    const double q = p[k];
    const Vec3 arm = v - machine.axes[k].origin + q * unit(k);
    d = d + data.epsilon[k].cross(arm) + q * data.direction_linear[k] + data.delta[k];
    v = arm;
  }
  return d;
}

Vec3 tip_error_and_jacobian(const Machine& machine, MachineData& data, const Vec3& p, Mat3& jacobian) {
  (void)machine;
  return exact_kernel<true>(data, p, &jacobian);
}

Points3 tip_error(const Machine& machine, const Eigen::Ref<const Points3>& points, Order order) {
  MachineData data(machine);
  Points3 out(points.rows(), 3);
  for (Eigen::Index i = 0; i < points.rows(); ++i) {
    const Vec3 p = points.row(i).transpose();
    for (int c = 0; c < 3; ++c) NETSHAPE_CHECK_FINITE("points", p[c]);
    out.row(i) = tip_error(machine, data, p, order).transpose();
  }
  return out;
}

Points3 actual_points(const Machine& machine, const Eigen::Ref<const Points3>& commanded, Order order) {
  Points3 e = tip_error(machine, commanded, order);
  return commanded + e;
}

Eigen::VectorXd volumetric_error(const Machine& machine, const Eigen::Ref<const Points3>& points, Order order) {
  const Points3 e = tip_error(machine, points, order);
  return e.rowwise().norm();
}

}  // namespace netshape::machine
