// The public synthesis API: one point (exact through the one-point chain kernel of lanes.cpp, first
// order here), many points as (n, 3) arrays, and R(a, b, c). The exact path tracks the deviation
// d = W − W_nominal directly, using R − I computed without cancellation, so small errors keep full
// relative precision.
#include "netshape/machine/synthesis.hpp"

#include "axis_components.hpp"
#include "netshape/core/error.hpp"
#include "rotation.hpp"

namespace netshape::machine {

namespace detail {
Vec3 exact_point(MachineData& data, const Vec3& p, Mat3* jacobian);  // lanes.cpp
}  // namespace detail

Mat3 rotation_zyx(double a, double b, double c) noexcept {
  return Mat3::Identity() + detail::rotation_minus_identity(a, b, c);
}

void evaluate_components(const Machine& machine, MachineData& data, const Vec3& p) {
  (void)machine;
  const CompiledMachine& cm = data.compiled();
  for (int k = 0; k < 3; ++k) {
    double e[6];
    if (const ErrorFunction* refused = detail::axis_components<false>(cm, k, p[k], e, nullptr))
      detail::throw_refused(*refused, p[k]);
    data.delta[k] = Vec3(e[0], e[1], e[2]);
    data.epsilon[k] = Vec3(e[3], e[4], e[5]);
  }
}

Vec3 tip_error(const Machine& machine, MachineData& data, const Vec3& p, Order order) {
  if (order == Order::exact) return detail::exact_point(data, p, nullptr);
  evaluate_components(machine, data, p);
  // First order: e₁ = Σ_k [δ_k + q_k (u'_k − u_k)₁ + ε_k × r_k] + L (θ × d), r_k the nominal arm from
  // carriage k's origin to the tip (tool side) or to the workpiece point (workpiece side).
  const CompiledMachine& cm = data.compiled();
  Vec3 v = cm.tip_nominal;
  Vec3 d = cm.tip_local_linear;
  for (const detail::ChainStep& st : cm.steps) {
    const int k = st.axis;
    const double q = p[k];
    if (st.tool) {
      d = d + data.epsilon[k].cross(v) + q * cm.direction_linear[k] + data.delta[k];
      v = st.origin + v + q * Vec3::Unit(k);
    } else {
      const Vec3 arm = v - st.origin + q * Vec3::Unit(k);
      d = d + data.epsilon[k].cross(arm) + q * cm.direction_linear[k] + data.delta[k];
      v = arm;
    }
  }
  return d;
}

Vec3 tip_error_and_jacobian(const Machine& machine, MachineData& data, const Vec3& p, Mat3& jacobian) {
  (void)machine;
  return detail::exact_point(data, p, &jacobian);
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
