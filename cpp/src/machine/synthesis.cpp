// Error synthesis along the two chains of a machine: exact product of homogeneous transforms and
// its first-order expansion (Yang & Kweon eq. 9-11 generalised). The exact path tracks the deviation
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

// ---- Many points at once: the exact kernel vectorised over points -------------------------------
// Each lane of a pack is one point and runs the operations of exact_kernel in the same order, so a
// lane gives the same numbers as the one-point function (to rounding where the AVX-512 code fuses
// multiply-adds). Component tables and mixed axes are looked
// up per lane (scalar), everything after them is vector code.
namespace {
template <int W>
struct LanePack;
#if defined(__GNUC__) && !defined(__clang__)
#define NETSHAPE_LANE_VECTORS 1
#define NETSHAPE_LANE_INLINE inline __attribute__((always_inline))
// 32-byte packs are returned from inlined helpers also in the baseline code (never instantiated
// there); the ABI note about passing AVX vectors does not apply to inlined calls.
#pragma GCC diagnostic ignored "-Wpsabi"
template <>
struct LanePack<2> {
  typedef double type __attribute__((vector_size(16)));
  typedef int itype __attribute__((vector_size(8)));
};
template <>
struct LanePack<4> {
  typedef double type __attribute__((vector_size(32)));
  typedef int itype __attribute__((vector_size(16)));
};
template <>
struct LanePack<8> {
  typedef double type __attribute__((vector_size(64)));
  typedef int itype __attribute__((vector_size(32)));
};
#else
#define NETSHAPE_LANE_INLINE inline
#endif
template <>
struct LanePack<1> {
  typedef double type;
};

template <class V>
NETSHAPE_LANE_INLINE V splat(double x) {
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
NETSHAPE_LANE_INLINE typename LanePack<W>::type gather_lanes(const double* const* row, int off) {
  if constexpr (W == 1) {
    return row[0][off];
  } else if constexpr (W == 2) {
    return typename LanePack<W>::type{row[0][off], row[1][off]};
  } else if constexpr (W == 4) {
    return typename LanePack<W>::type{row[0][off], row[1][off], row[2][off], row[3][off]};
  } else {
    return typename LanePack<W>::type{row[0][off], row[1][off], row[2][off], row[3][off],
                                      row[4][off], row[5][off], row[6][off], row[7][off]};
  }
}
template <class V>
NETSHAPE_LANE_INLINE V load_lanes(const double* x) {
  V v;
  __builtin_memcpy(&v, x, sizeof v);
  return v;
}
template <class V>
NETSHAPE_LANE_INLINE void store_lanes(double* x, const V& v) {
  __builtin_memcpy(x, &v, sizeof v);
}

// Six components of axis k at q into v[6] (slopes into s[6] when slope); false when q leaves a table
// whose policy is `error` or is not finite (then v and s are zeros), instead of throwing.
bool axis_lane(const MachineData& data, int k, double q, bool slope, double* v, double* s) {
  const detail::AxisKernel& ker = data.kernels[k];
  if (ker.mode == detail::AxisKernel::Mode::table && ker.out_of_range == OutOfRange::error) {
    if (!(q >= ker.lo && q <= ker.hi)) {
      for (int c = 0; c < 6; ++c) v[c] = s[c] = 0.0;
      return false;
    }
  } else if (ker.mode == detail::AxisKernel::Mode::generic) {
    for (int c = 0; c < 6; ++c) {
      const detail::PreparedFunction& f = data.functions[k * 6 + c];
      if (f.kind == ErrorFunction::Kind::table && !(q >= f.lo && q <= f.hi) &&
          (f.out_of_range == OutOfRange::error || !std::isfinite(q))) {
        for (int j = 0; j < 6; ++j) v[j] = s[j] = 0.0;
        return false;
      }
    }
  }
  if (!std::isfinite(q)) {
    for (int c = 0; c < 6; ++c) v[c] = s[c] = 0.0;
    return false;
  }
  if (slope)
    evaluate_axis<true>(data, k, q, v, s);
  else
    evaluate_axis<false>(data, k, q, v, s);
  return true;
}

// One pack of W points starting at lane `first` of the batch arrays. Axis by axis along the chain:
// its six components, sin/cos − 1 of its angles, its 3×3 step (few values live at a time).
template <int W, bool Jacobian>
NETSHAPE_LANE_INLINE unsigned lanes_pack(MachineData& data, const double (&pin)[3][batch_lanes], int first,
                                         double (&out)[3][batch_lanes], double (*jac)[9][batch_lanes]) {
  using V = typename LanePack<W>::type;
  unsigned bad = 0;
  V P[3];
  for (int c = 0; c < 3; ++c) P[c] = load_lanes<V>(&pin[c][first]);
  {
    const V z = (P[0] - P[0]) + (P[1] - P[1]) + (P[2] - P[2]);  // 0 where the point is finite, else NaN
    for (int w = 0; w < W; ++w) {
      double zw;
      if constexpr (W == 1)
        zw = z;
      else
        zw = z[w];
      if (!(zw == 0.0)) bad |= 1u << (first + w);
    }
  }
  // How each axis' components are evaluated: a polynomial axis by a six-component Horner on its packed
  // coefficients (the values of the 18-lane Horner of exact_kernel), a uniform table with every lane
  // inside it by vector interpolation, anything else per lane (other tables, lanes outside a table,
  // mixed axes) into ev/sv (lane layout of MachineData::lane_coefficients).
  enum : unsigned char { axis_poly, axis_table, per_lane };
  unsigned char how[3];
  for (int k = 0; k < 3; ++k) {
    const detail::AxisKernel& ker = data.kernels[k];
    if (ker.mode == detail::AxisKernel::Mode::polynomial) {
      // (zero padding to the machine's highest degree, as lane_coefficients has, changes no value)
      how[k] = axis_poly;
    } else if (ker.mode == detail::AxisKernel::Mode::table && ker.uniform) {
      bool inside = true;
      for (int w = 0; w < W; ++w) {
        const double q = pin[k][first + w];
        inside = inside && q >= ker.lo && q <= ker.hi;
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
      double v[6], d[6];
      if (!axis_lane(data, k, pin[k][first + w], Jacobian, v, d)) bad |= 1u << (first + w);
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
  V v0 = splat<V>(data.tip_nominal[0]), v1 = splat<V>(data.tip_nominal[1]), v2 = splat<V>(data.tip_nominal[2]);
  V d0 = splat<V>(data.tip_local[0]), d1 = splat<V>(data.tip_local[1]), d2 = splat<V>(data.tip_local[2]);
  V arm[3][3], eps[3][3], eps_slope[3][3], delta_slope[3][3];
  V curv[3][6];  // second derivatives of the components of a polynomial axis (0 otherwise), as e[]
  // exact Jacobian by forward differentiation along the chain: D[r][m] = ∂d_r/∂q_m
  V D[3][3];
  if (Jacobian)
    for (int r = 0; r < 3; ++r)
      for (int m = 0; m < 3; ++m) D[r][m] = splat<V>(0.0);
  bool added[3] = {false, false, false};  // axis m's q_m e_m is in the nominal position v
  const V one = splat<V>(1.0);
  V big = splat<V>(0.0);  // largest squared angle of each lane
  for (int i = 0; i < 3; ++i) {
    const detail::ChainStep& st = data.steps[i];
    const int k = st.axis;
    const V q = P[k];
    // e[0..2]: angles (EAk, EBk, ECk) [rad], e[3..5]: translations (EXk, EYk, EZk) [mm]
    V e[6], sl[6], s2[6];
    const int lane[6] = {3 * k, 3 * k + 1, 3 * k + 2, 9 + 3 * k, 10 + 3 * k, 11 + 3 * k};
    if (how[k] == axis_poly) {
      // as evaluate_axis: packed [j * 6 + c], translations c = 0..2, rotations 3..5
      const detail::AxisKernel& ker = data.kernels[k];
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
          if (Jacobian) {
            s2[c] = s2[c] * q + sl[c];
            sl[c] = sl[c] * q + e[c];
          }
          e[c] = e[c] * q + cj[comp[c]];
        }
      }
      if (Jacobian)
        for (int c = 0; c < 6; ++c) curv[k][c] = s2[c] + s2[c];
    } else if (how[k] == axis_table) {
      // as evaluate_axis on a uniform table, every lane inside it: one row lookup per lane
      const detail::AxisKernel& ker = data.kernels[k];
      const V u = (q - ker.lo) * ker.inv_step;
      V fi;
      const double* row[W];
      if constexpr (W == 1) {
        int i = static_cast<int>(u);
        if (i > ker.terms - 2) i = ker.terms - 2;
        fi = i;
        row[0] = ker.packed.data() + static_cast<std::ptrdiff_t>(i) * 6;
      } else {
        using I = typename LanePack<W>::itype;
        I iv = __builtin_convertvector(u, I);  // truncation, as static_cast<int>
        const I top = iv - iv + (ker.terms - 2);
        iv = iv > top ? top : iv;
        fi = __builtin_convertvector(iv, V);
        for (int w = 0; w < W; ++w) row[w] = ker.packed.data() + static_cast<std::ptrdiff_t>(iv[w]) * 6;
      }
      const V t = u - fi;
      const int comp[6] = {3, 4, 5, 0, 1, 2};
#pragma GCC unroll 6
      for (int c = 0; c < 6; ++c) {
        const V a = gather_lanes<W>(row, comp[c]), b = gather_lanes<W>(row, 6 + comp[c]);
        const V dv = b - a;
        e[c] = a + t * dv;
        if (Jacobian) sl[c] = dv * ker.inv_step;
      }
      if (Jacobian)
        for (int c = 0; c < 6; ++c) curv[k][c] = splat<V>(0.0);
    } else {
#pragma GCC unroll 6
      for (int c = 0; c < 6; ++c) {
        e[c] = load_lanes<V>(ev[lane[c]]);
        if (Jacobian) sl[c] = load_lanes<V>(sv[lane[c]]);
      }
      if (Jacobian)
        for (int c = 0; c < 6; ++c) curv[k][c] = splat<V>(0.0);
    }
    if (Jacobian) {
      for (int c = 0; c < 3; ++c) {
        eps[k][c] = e[c];
        eps_slope[k][c] = sl[c];
        delta_slope[k][c] = sl[3 + c];
      }
    }
    // sin and cos − 1: the short Taylor series of sincos_lanes, exact to rounding when every
    // |angle| < 1e-3; a lane with a larger angle is evaluated again by the one-point kernel below.
    V sn[3], cm[3];
    {
      constexpr double k6 = -1.0 / 6.0, k120 = 1.0 / 120.0, k24 = 1.0 / 24.0, k720 = -1.0 / 720.0;
#pragma GCC unroll 3
      for (int c = 0; c < 3; ++c) {
        const V x2 = e[c] * e[c];
        big = big > x2 ? big : x2;
        sn[c] = e[c] + e[c] * x2 * (k6 + x2 * k120);
        cm[c] = x2 * (-0.5 + x2 * (k24 + x2 * k720));
      }
    }
    const V sa = sn[0], sb = sn[1], sc = sn[2];
    const V cma = cm[0], cmb = cm[1], cmc = cm[2];
    const V ca = one + cma, cb = one + cmb, cc = one + cmc;
    const V sasb = sa * sb, casb = ca * sb;
    const V m00 = cmb + cmc + cmb * cmc, m01 = sasb * cc - ca * sc, m02 = casb * cc + sa * sc;
    const V m10 = cb * sc, m11 = sasb * sc + cma + cmc + cma * cmc, m12 = casb * sc - sa * cc;
    const V m20 = -sb, m21 = sa * cb, m22 = cma + cmb + cma * cmb;
    const Vec3& du = data.direction[k];
    const V t0 = q * du[0] + e[3], t1 = q * du[1] + e[4], t2 = q * du[2] + e[5];
    V c0, c1, c2;
    if (st.tool) {
      if (Jacobian) arm[k][0] = v0, arm[k][1] = v1, arm[k][2] = v2;
      c0 = m00 * v0 + m01 * v1 + m02 * v2 + t0;
      c1 = m10 * v0 + m11 * v1 + m12 * v2 + t1;
      c2 = m20 * v0 + m21 * v1 + m22 * v2 + t2;
      // v += origin + q u (the same additions as exact_kernel: origin + (q or 0) first)
      const V o0 = k == 0 ? st.origin[0] + q : splat<V>(st.origin[0]);
      const V o1 = k == 1 ? st.origin[1] + q : splat<V>(st.origin[1]);
      const V o2 = k == 2 ? st.origin[2] + q : splat<V>(st.origin[2]);
      v0 += o0, v1 += o1, v2 += o2;
    } else {
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
    if (Jacobian) {
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
  if (Jacobian)
    for (int m = 0; m < 3; ++m)
      for (int r = 0; r < 3; ++r) store_lanes(&data.lane_jacobian[3 * m + r][first], D[r][m]);
  store_lanes(&out[0][first], d0);
  store_lanes(&out[1][first], d1);
  store_lanes(&out[2][first], d2);
  unsigned redo = 0;
  for (int w = 0; w < W; ++w) {
    double b;
    if constexpr (W == 1)
      b = big;
    else
      b = big[w];
    if (!(b < 1e-6)) redo |= 1u << w;
  }
  if (Jacobian) {
    // column k = δ'_k + (u'_k − u_k)₁ + ε'_k × r_k + (Σ_{j: arm grows with q_k} ε_j) × u_k
    for (int k = 0; k < 3; ++k) {
      V es0 = splat<V>(0.0), es1 = es0, es2 = es0;
      for (int j = 0; j < 3; ++j)
        if (data.arm_grows[k][j]) es0 += eps[j][0], es1 += eps[j][1], es2 += eps[j][2];
      const V a0 = eps_slope[k][0], a1 = eps_slope[k][1], a2 = eps_slope[k][2];
      const V r0 = arm[k][0], r1 = arm[k][1], r2 = arm[k][2];
      const V col[3] = {a1 * r2 - a2 * r1, a2 * r0 - a0 * r2, a0 * r1 - a1 * r0};
      // (es × u_k): x̂ → (0, es2, −es1); ŷ → (−es2, 0, es0); ẑ → (es1, −es0, 0)
      const V zero = splat<V>(0.0);
      const V x[3] = {k == 0 ? zero : (k == 1 ? -es2 : es1), k == 0 ? es2 : (k == 1 ? zero : -es0),
                      k == 0 ? -es1 : (k == 1 ? es0 : zero)};
      for (int r = 0; r < 3; ++r) {
        const V c = delta_slope[k][r] + data.direction_linear[k][r] + col[r] + x[r];
        store_lanes(&(*jac)[3 * k + r][first], c);
      }
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
  // lanes with an angle ≥ 1e-3 rad (not a realistic geometric error, but allowed): the one-point kernel
  redo &= ~(bad >> first);
  if (redo) {
    for (int w = 0; w < W; ++w) {
      if (!((redo >> w) & 1u)) continue;
      const Vec3 pw(pin[0][first + w], pin[1][first + w], pin[2][first + w]);
      Vec3 ew;
      if (Jacobian) {
        Mat3 jw;
        ew = exact_kernel<true>(data, pw, &jw);
        for (int col = 0; col < 3; ++col)
          for (int r = 0; r < 3; ++r) (*jac)[3 * col + r][first + w] = jw(r, col);
      } else {
        ew = exact_kernel<false>(data, pw, nullptr);
      }
      for (int c = 0; c < 3; ++c) out[c][first + w] = ew[c];
    }
  }
  return bad;
}

template <int W>
NETSHAPE_LANE_INLINE unsigned lanes_impl(MachineData& data, const double (&p)[3][batch_lanes],
                                         double (&e)[3][batch_lanes], double (*jac)[9][batch_lanes]) {
  unsigned bad = 0;
  if (jac) {
    for (int f = 0; f < batch_lanes; f += W) bad |= lanes_pack<W, true>(data, p, f, e, jac);
  } else {
    for (int f = 0; f < batch_lanes; f += W) bad |= lanes_pack<W, false>(data, p, f, e, nullptr);
  }
  return bad;
}

using LanesFn = unsigned (*)(MachineData&, const double (&)[3][batch_lanes], double (&)[3][batch_lanes],
                             double (*)[9][batch_lanes]);
#if defined(NETSHAPE_LANE_VECTORS)
unsigned lanes_base(MachineData& data, const double (&p)[3][batch_lanes], double (&e)[3][batch_lanes],
                    double (*jac)[9][batch_lanes]) {
  return lanes_impl<2>(data, p, e, jac);
}
#if defined(__x86_64__)
__attribute__((target("avx2"))) unsigned lanes_avx2(MachineData& data, const double (&p)[3][batch_lanes],
                                                    double (&e)[3][batch_lanes], double (*jac)[9][batch_lanes]) {
  return lanes_impl<4>(data, p, e, jac);
}
__attribute__((target("avx512f"))) unsigned lanes_avx512(MachineData& data, const double (&p)[3][batch_lanes],
                                                          double (&e)[3][batch_lanes], double (*jac)[9][batch_lanes]) {
  return lanes_impl<8>(data, p, e, jac);
}
#endif
LanesFn pick_lanes() {
#if defined(__x86_64__)
  if (__builtin_cpu_supports("avx512f")) return &lanes_avx512;
  if (__builtin_cpu_supports("avx2")) return &lanes_avx2;
#endif
  return &lanes_base;
}
#else
unsigned lanes_scalar(MachineData& data, const double (&p)[3][batch_lanes], double (&e)[3][batch_lanes],
                      double (*jac)[9][batch_lanes]) {
  return lanes_impl<1>(data, p, e, jac);
}
LanesFn pick_lanes() { return &lanes_scalar; }
#endif
}  // namespace

unsigned tip_error_lanes(MachineData& data, const double (&p)[3][batch_lanes], double (&e)[3][batch_lanes],
                         double (*jacobian)[9][batch_lanes]) {
  static const LanesFn fn = pick_lanes();
  return fn(data, p, e, jacobian);
}

bool detail::lanes_width_supported(int width) {
#if defined(NETSHAPE_LANE_VECTORS)
#if defined(__x86_64__)
  if (width == 8) return __builtin_cpu_supports("avx512f");
  if (width == 4) return __builtin_cpu_supports("avx2");
#endif
  return width == 2;
#else
  return width == 1;
#endif
}

unsigned detail::tip_error_lanes_width(int width, MachineData& data, const double (&p)[3][batch_lanes],
                                       double (&e)[3][batch_lanes], double (*jacobian)[9][batch_lanes]) {
  NETSHAPE_CHECK(lanes_width_supported(width), "width", width, "must be a vector width this CPU runs");
#if defined(NETSHAPE_LANE_VECTORS)
#if defined(__x86_64__)
  if (width == 8) return lanes_avx512(data, p, e, jacobian);
  if (width == 4) return lanes_avx2(data, p, e, jacobian);
#endif
  return lanes_base(data, p, e, jacobian);
#else
  return lanes_scalar(data, p, e, jacobian);
#endif
}

}  // namespace netshape::machine
