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
  }
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
  }
}

namespace {
inline void evaluate_components_inline(MachineData& data, const Vec3& p) {
  for (int k = 0; k < 3; ++k) {
    const detail::PreparedFunction* f = &data.functions[k * 6];
    const double q = p[k];
    data.delta[k] = Vec3(eval_prepared(f[0], q), eval_prepared(f[1], q), eval_prepared(f[2], q));
    data.epsilon[k] = Vec3(eval_prepared(f[3], q), eval_prepared(f[4], q), eval_prepared(f[5], q));
  }
}

}  // namespace

void evaluate_components(const Machine& machine, MachineData& data, const Vec3& p) {
  (void)machine;
  evaluate_components_inline(data, p);
}

Vec3 tip_error(const Machine& machine, MachineData& data, const Vec3& p, Order order) {
  evaluate_components_inline(data, p);
  // v: nominal position of the point in the current frame; d: its deviation (actual - nominal).
  Vec3 v = data.tip_nominal;
  Vec3 d = order == Order::exact ? data.tip_local : data.tip_local_linear;
  const auto& tc = machine.tool_chain;
  for (auto it = tc.rbegin(); it != tc.rend(); ++it) {
    const int k = *it;
    const double q = p[k];
    const Vec3& o = machine.axes[k].origin;
    // v_frame = o + R (v + d) + q u' + δ ; nominal o + v + q u
    if (order == Order::exact) {
      const Mat3 rm = rotation_minus_identity(data.epsilon[k][0], data.epsilon[k][1], data.epsilon[k][2]);
      d = d + rm * (v + d) + q * data.direction[k] + data.delta[k];
    } else {
      d = d + data.epsilon[k].cross(v) + q * data.direction_linear[k] + data.delta[k];
    }
    v = o + v + q * unit(k);
  }
  for (int k : machine.workpiece_chain) {
    const double q = p[k];
    const Vec3& o = machine.axes[k].origin;
    // The table moves by -t = -(q u' + δ) and turns by R^-1 about its own origin:
    // W = R (v + d - o + t) ; nominal v - o + q u. The arm of the rotation is the point relative to
    // the carriage's current origin (seeds/003 eq. 9: T_z + L + Ozx_z + Oxy_z - z).
    const Vec3 t_dev = q * data.direction[k] + data.delta[k];  // t - q u
    if (order == Order::exact) {
      const Mat3 rm = rotation_minus_identity(data.epsilon[k][0], data.epsilon[k][1], data.epsilon[k][2]);
      const Vec3 arm = v - o + q * unit(k);
      d = d + t_dev + rm * (arm + d + t_dev);
    } else {
      d = d + data.epsilon[k].cross(v - o + q * unit(k)) + q * data.direction_linear[k] + data.delta[k];
    }
    v = v - o + q * unit(k);
  }
  return d;
}

Vec3 tip_error_and_jacobian(const Machine& machine, MachineData& data, const Vec3& p, Mat3& jacobian) {
  for (int k = 0; k < 3; ++k) {
    const detail::PreparedFunction* f = &data.functions[k * 6];
    const double q = p[k];
    for (int c = 0; c < 3; ++c) {
      data.delta[k][c] = eval_prepared_slope(f[c], q, data.delta_slope[k][c]);
      data.epsilon[k][c] = eval_prepared_slope(f[3 + c], q, data.epsilon_slope[k][c]);
    }
  }
  // Exact error with the components just evaluated (same steps as tip_error).
  Vec3 v = data.tip_nominal;
  Vec3 d = data.tip_local;
  std::array<Vec3, 3> arm;  // nominal Abbe arm of each axis
  const auto& tc = machine.tool_chain;
  for (auto it = tc.rbegin(); it != tc.rend(); ++it) {
    const int k = *it;
    const double q = p[k];
    arm[k] = v;
    const Mat3 rm = rotation_minus_identity(data.epsilon[k][0], data.epsilon[k][1], data.epsilon[k][2]);
    d = d + rm * (v + d) + q * data.direction[k] + data.delta[k];
    v = machine.axes[k].origin + v + q * unit(k);
  }
  for (int k : machine.workpiece_chain) {
    const double q = p[k];
    const Vec3 t_dev = q * data.direction[k] + data.delta[k];
    const Mat3 rm = rotation_minus_identity(data.epsilon[k][0], data.epsilon[k][1], data.epsilon[k][2]);
    arm[k] = v - machine.axes[k].origin + q * unit(k);
    d = d + t_dev + rm * (arm[k] + d + t_dev);
    v = arm[k];
  }
  // First-order Jacobian: column k = δ'_k + s_k + ε'_k × r_k + (Σ_{j whose arm grows with q_k} ε_j) × u_k.
  std::array<int, 3> tool_pos{-1, -1, -1}, work_pos{-1, -1, -1};
  for (std::size_t i = 0; i < tc.size(); ++i) tool_pos[tc[i]] = static_cast<int>(i);
  for (std::size_t i = 0; i < machine.workpiece_chain.size(); ++i) work_pos[machine.workpiece_chain[i]] = static_cast<int>(i);
  for (int k = 0; k < 3; ++k) {
    Vec3 eps_sum = Vec3::Zero();
    for (int j = 0; j < 3; ++j) {
      const bool grows = tool_pos[k] >= 0 ? (tool_pos[j] >= 0 ? tool_pos[j] < tool_pos[k] : true)
                                          : (work_pos[j] >= 0 && work_pos[j] >= work_pos[k]);
      if (grows) eps_sum += data.epsilon[j];
    }
    jacobian.col(k) = data.delta_slope[k] + data.direction_linear[k] + data.epsilon_slope[k].cross(arm[k]) +
                      eps_sum.cross(unit(k));
  }
  return d;
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
