// Volumetric compensation of CL points: fixed-point iteration on P_cmd + e(P_cmd) = P_nom with a
// Newton fallback (finite-difference Jacobian) when the fixed point contracts slowly.
#include "netshape/compensation/volumetric_compensation.hpp"

#include <cmath>
#include <sstream>
#include <stdexcept>

#include "netshape/core/error.hpp"
#include "netshape/machine/synthesis.hpp"

namespace netshape::compensation {

using machine::Machine;
using machine::MachineData;

void VolumetricOptions::validate() const {
  NETSHAPE_CHECK(std::isfinite(tolerance) && tolerance > 0, "tolerance", tolerance,
                 "must be a finite number > 0 [mm]");
  NETSHAPE_CHECK(max_iterations >= 1, "max_iterations", max_iterations, "must be ≥ 1");
}

bool VolumetricResult::all_ok() const { return first_failure() < 0; }

long VolumetricResult::first_failure() const {
  for (std::size_t i = 0; i < status.size(); ++i)
    if (status[i] != VolumetricStatus::ok) return static_cast<long>(i);
  return -1;
}

namespace {
// One point. `step_matrix` is (I + J₁)⁻¹ of the first-order model; when `have_step` is true on entry it
// comes from a neighbouring point (path) and is reused — it differs from the one here by O(J' · distance),
// which only slows convergence, never changes the fixed point — otherwise it is computed at the start.
VolumetricStatus solve_point(const Machine& machine, MachineData& data, const Vec3& nominal, const Vec3& start,
                             const VolumetricOptions& options, Mat3& step_matrix, bool& have_step, bool& computed,
                             Vec3& commanded, double& residual, int& iterations, int& axis) {
  computed = false;
  axis = -1;
  iterations = 0;
  Vec3 p = start;
  residual = INFINITY;
  bool newton = false;
  bool fresh = false;  // step_matrix computed at a point of this solve
  const double tol2 = options.tolerance * options.tolerance;
  try {
    while (iterations < options.max_iterations) {
      Vec3 r;
      if (!have_step) {
        // Chord Newton: the first-order Jacobian, reused for every step. It differs from the exact
        // Jacobian by O(error²), so each step gains ~8 digits instead of the plain fixed point's ~4;
        // the residual below is always the exact one.
        Mat3 jac;
        r = p + machine::tip_error_and_jacobian(machine, data, p, jac) - nominal;
        const Mat3 a = Mat3::Identity() + jac;
        const double det = a.determinant();
        step_matrix = std::isfinite(det) && std::abs(det) > 1e-6 ? Mat3(a.inverse()) : Mat3::Identity();
        have_step = true;
        fresh = true;
        computed = true;
      } else {
        r = p + machine::tip_error(machine, data, p) - nominal;
      }
      ++iterations;
      const double rn2 = r.squaredNorm();
      if (rn2 <= tol2) {
        residual = std::sqrt(rn2);
        break;
      }
      const double rn = std::sqrt(rn2);
      if (!newton && rn > 0.5 * residual) {
        // slow contraction: first a Jacobian at the current point, then Newton with finite differences
        if (fresh) {
          newton = true;
        } else {
          have_step = false;  // the next evaluation computes it
        }
      }
      residual = rn;
      if (iterations >= options.max_iterations) break;
      if (!newton) {
        p -= step_matrix * r;
      } else {
        // Jacobian of p + e(p) by central differences; step small against the scale of p.
        Mat3 jac;
        const double h = 1e-4;
        for (int c = 0; c < 3; ++c) {
          Vec3 a = p, b = p;
          a[c] += h;
          b[c] -= h;
          const Vec3 fa = a + machine::tip_error(machine, data, a);
          const Vec3 fb = b + machine::tip_error(machine, data, b);
          jac.col(c) = (fa - fb) / (2 * h);
        }
        const Eigen::FullPivLU<Mat3> lu(jac);
        if (!lu.isInvertible()) break;
        p -= lu.solve(r);
      }
      if (!p.allFinite()) break;
    }
  } catch (const std::invalid_argument&) {
    commanded = p;
    return VolumetricStatus::outside_table;
  }
  commanded = p;
  if (!(residual <= options.tolerance)) return VolumetricStatus::not_converged;
  if (options.check_travel) {
    for (int k = 0; k < 3; ++k) {
      const auto& a = machine.axes[k];
      if (p[k] < a.travel_min || p[k] > a.travel_max) {
        axis = k;
        return VolumetricStatus::outside_travel;
      }
    }
  }
  return VolumetricStatus::ok;
}
}  // namespace

VolumetricStatus compensate_point(const Machine& machine, MachineData& data, const Vec3& nominal,
                                  const VolumetricOptions& options, Vec3& commanded, double& residual,
                                  int& iterations, int& axis) {
  Mat3 step_matrix;
  bool have_step = false, computed = false;
  return solve_point(machine, data, nominal, nominal, options, step_matrix, have_step, computed, commanded,
                     residual, iterations, axis);
}

VolumetricResult compensate_points_status(const Machine& machine, const Eigen::Ref<const Points3>& nominal,
                                          const VolumetricOptions& options) {
  options.validate();
  MachineData data(machine);
  const Eigen::Index n = nominal.rows();
  VolumetricResult res;
  res.commanded.resize(n, 3);
  res.residual.resize(n);
  res.iterations.resize(n);
  res.axis.resize(n);
  res.status.resize(static_cast<std::size_t>(n));
  bool have_prev = false;
  Vec3 prev_correction = Vec3::Zero();
  Vec3 prev_nominal = Vec3::Zero();
  Mat3 step_matrix = Mat3::Identity();
  Vec3 step_at = Vec3::Zero();  // nominal point where step_matrix was computed
  for (Eigen::Index i = 0; i < n; ++i) {
    const Vec3 p = nominal.row(i).transpose();
    for (int c = 0; c < 3; ++c) NETSHAPE_CHECK_FINITE("nominal points", p[c]);
    Vec3 cmd;
    double r;
    int it, ax;
    // Warm start: neighbouring CL points need nearly the same correction, so start from the
    // previous point's correction (one evaluation fewer along a path; same fixed point).
    // Only for a neighbour within 10 mm: the correction of a far point is no better a guess than 0.
    // The step matrix of a point within 10 mm of where it was computed is reused as well (no
    // Jacobian along a path).
    const bool warm = have_prev && (p - prev_nominal).squaredNorm() < 100.0;
    const Vec3 start = warm ? Vec3(p + prev_correction) : p;
    bool have_step = warm && (p - step_at).squaredNorm() < 100.0, computed = false;
    res.status[i] = solve_point(machine, data, p, start, options, step_matrix, have_step, computed, cmd, r, it, ax);
    if (computed) step_at = p;  // (computed near p: at the start or an iterate)
    have_prev = res.status[i] == VolumetricStatus::ok;
    if (have_prev) {
      prev_correction = cmd - p;
      prev_nominal = p;
    }
    res.commanded.row(i) = cmd.transpose();
    res.residual[i] = r;
    res.iterations[i] = it;
    res.axis[i] = ax;
  }
  return res;
}

Points3 compensate_points(const Machine& machine, const Eigen::Ref<const Points3>& nominal,
                          const VolumetricOptions& options) {
  VolumetricResult res = compensate_points_status(machine, nominal, options);
  const long i = res.first_failure();
  if (i < 0) return std::move(res.commanded);
  std::ostringstream os;
  os.precision(12);
  const Vec3 p = nominal.row(i).transpose();
  const Vec3 c = res.commanded.row(i).transpose();
  os << "point " << i << " (" << p.x() << ", " << p.y() << ", " << p.z() << ") mm: ";
  switch (res.status[i]) {
    case VolumetricStatus::outside_travel: {
      const int k = res.axis[i];
      const auto& a = machine.axes[k];
      os << "compensated axis " << "XYZ"[k] << " = " << c[k] << " mm is outside its travel [" << a.travel_min
         << ", " << a.travel_max << "] mm";
      throw std::invalid_argument(os.str());
    }
    case VolumetricStatus::outside_table: {
      // re-evaluate to get the table's own message
      MachineData data(machine);
      try {
        machine::tip_error(machine, data, c);
      } catch (const std::invalid_argument& e) {
        os << e.what();
      }
      throw std::invalid_argument(os.str());
    }
    default:
      os << "volumetric compensation did not converge: residual " << res.residual[i] << " mm after "
         << res.iterations[i] << " evaluations (tolerance " << options.tolerance << " mm)";
      throw Error(os.str());
  }
}

}  // namespace netshape::compensation
