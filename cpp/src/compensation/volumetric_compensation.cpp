// Volumetric compensation of CL points: fixed-point iteration on P_cmd + e(P_cmd) = P_nom with a
// Newton fallback (finite-difference Jacobian) when the fixed point contracts slowly.
#include "netshape/compensation/volumetric_compensation.hpp"

#include <array>
#include <cmath>
#include <vector>
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

namespace {
constexpr int lanes = machine::batch_lanes;

// (I + J)⁻¹ of every lane (J column-major in jac[3 * col + row][l]) into m (row-major, m[3 * row + col][l])
// by cofactors; identity for a lane where I + J is (nearly) singular, as solve_point does. Branch-free
// loops over the lanes (vectorised).
inline void step_matrices(const double (&jac)[9][lanes], double (&m)[9][lanes]) {
  for (int l = 0; l < lanes; ++l) {
    const double a00 = 1.0 + jac[0][l], a10 = jac[1][l], a20 = jac[2][l];
    const double a01 = jac[3][l], a11 = 1.0 + jac[4][l], a21 = jac[5][l];
    const double a02 = jac[6][l], a12 = jac[7][l], a22 = 1.0 + jac[8][l];
    const double c00 = a11 * a22 - a12 * a21, c01 = a12 * a20 - a10 * a22, c02 = a10 * a21 - a11 * a20;
    const double det = a00 * c00 + a01 * c01 + a02 * c02;
    const bool ok = std::abs(det) > 1e-6 && std::abs(det) < INFINITY;
    const double f = ok ? 1.0 / det : 0.0;
    const double id = ok ? 0.0 : 1.0;
    m[0][l] = c00 * f + id;
    m[1][l] = (a02 * a21 - a01 * a22) * f;
    m[2][l] = (a01 * a12 - a02 * a11) * f;
    m[3][l] = c01 * f;
    m[4][l] = (a00 * a22 - a02 * a20) * f + id;
    m[5][l] = (a02 * a10 - a00 * a12) * f;
    m[6][l] = c02 * f;
    m[7][l] = (a01 * a20 - a00 * a21) * f;
    m[8][l] = (a00 * a11 - a01 * a10) * f + id;
  }
}
}  // namespace

VolumetricResult compensate_points_status(const Machine& machine, const Eigen::Ref<const Points3>& nominal,
                                          const VolumetricOptions& options) {
  options.validate();
  MachineData data(machine);
  const Eigen::Index n = nominal.rows();
  for (Eigen::Index i = 0; i < n; ++i)
    for (int c = 0; c < 3; ++c) NETSHAPE_CHECK_FINITE("nominal points", nominal(i, c));
  VolumetricResult res;
  res.commanded.resize(n, 3);
  res.residual.resize(n);
  res.iterations.resize(n);
  res.axis.resize(n);
  res.status.resize(static_cast<std::size_t>(n));
  // The chord-Newton iteration of solve_point, run for `lanes` points at once (one point of each
  // stream per block) so that one vectorised evaluation serves them all. A point whose iteration
  // leaves the fast path (slow contraction after a fresh step matrix, max_iterations, a table left,
  // not finite) is solved again one by one (compensate_point, cold start) afterwards: its result and
  // status are that function's.
  //
  // Lane l solves the contiguous run [next[l], end[l]) of the input point after point: along a path it
  // warm-starts from its own previous point and reuses its step matrix exactly as the one-by-one loop
  // does. Per-lane state is kept as structure of arrays [..][lane].
  Eigen::Index next[lanes], end[lanes];
  bool have_prev[lanes], have_matrix[lanes];
  double prev_correction[3][lanes], prev_nominal[3][lanes], step_at[3][lanes];
  for (int l = 0; l < lanes; ++l) {
    next[l] = n * l / lanes;
    end[l] = n * (l + 1) / lanes;
    have_prev[l] = have_matrix[l] = false;
    for (int c = 0; c < 3; ++c) prev_correction[c][l] = prev_nominal[c][l] = step_at[c][l] = 0.0;
  }
  std::vector<Eigen::Index> again;
  const double travel_min[3] = {machine.axes[0].travel_min, machine.axes[1].travel_min, machine.axes[2].travel_min};
  const double travel_max[3] = {machine.axes[0].travel_max, machine.axes[1].travel_max, machine.axes[2].travel_max};
  const double tol2 = options.tolerance * options.tolerance;
  const int max_iterations = options.max_iterations;
  enum : unsigned char { idle = 0, active = 1, done = 2, failed = 3 };
  double N[3][lanes], P[3][lanes], e[3][lanes], jac[9][lanes];
  double residual[lanes];  // squared residual of the last evaluation [mm²]
  double S[9][lanes];  // the lane's step matrix (I + J)⁻¹ (exact J), row-major, kept from point to point
  for (int j = 0; j < 9; ++j)
    for (int l = 0; l < lanes; ++l) S[j][l] = j % 4 == 0 ? 1.0 : 0.0;
  int iterations[lanes];
  unsigned char state[lanes];
  bool have_step[lanes], fresh[lanes], computed[lanes], second[lanes];
  // grows[m][k]: axis k's Abbe arm grows with q_m (second-order step)
  const auto& grows = data.compiled().arm_grows;
  Eigen::Index index[lanes];
  for (;;) {
    // a point from each stream
    int running = 0;
    for (int l = 0; l < lanes; ++l) {
      if (next[l] >= end[l]) {
        state[l] = idle;
        index[l] = -1;
        for (int c = 0; c < 3; ++c) P[c][l] = N[c][l] = 0.0;  // evaluated, unused
        have_step[l] = true;
        continue;
      }
      ++running;
      const Eigen::Index i = next[l]++;
      index[l] = i;
      double d2p = 0.0, d2s = 0.0;
      for (int c = 0; c < 3; ++c) {
        const double x = nominal(i, c);
        N[c][l] = x;
        d2p += (x - prev_nominal[c][l]) * (x - prev_nominal[c][l]);
        d2s += (x - step_at[c][l]) * (x - step_at[c][l]);
      }
      // warm start from the lane's previous point within 10 mm; its step matrix within 10 mm of where it
      // was computed
      const bool warm = have_prev[l] && d2p < 100.0;
      for (int c = 0; c < 3; ++c) P[c][l] = warm ? N[c][l] + prev_correction[c][l] : N[c][l];
      have_step[l] = warm && have_matrix[l] && d2s < 100.0;
      state[l] = active;
      residual[l] = INFINITY;
      iterations[l] = 0;
      fresh[l] = computed[l] = false;
    }
    if (running == 0) break;
    for (;;) {
      bool need_jacobian = false;
      for (int l = 0; l < lanes; ++l) need_jacobian |= state[l] == active && !have_step[l];
      const unsigned bad = machine::tip_error_lanes(data, P, e, need_jacobian ? &jac : nullptr);
      for (int l = 0; l < lanes; ++l) second[l] = false;
      if (need_jacobian) {
        double m[9][lanes];
        step_matrices(data.lane_jacobian, m);  // the exact Jacobian (jac: first order)
        for (int l = 0; l < lanes; ++l) {
          if (state[l] != active || have_step[l]) continue;
          for (int j = 0; j < 9; ++j) S[j][l] = m[j][l];
          have_step[l] = fresh[l] = computed[l] = second[l] = true;
        }
      }
      int still = 0;
      for (int l = 0; l < lanes; ++l) {
        if (state[l] != active) continue;
        if ((bad >> l) & 1u) {
          state[l] = failed;
          continue;
        }
        const double r0 = P[0][l] + e[0][l] - N[0][l];
        const double r1 = P[1][l] + e[1][l] - N[1][l];
        const double r2 = P[2][l] + e[2][l] - N[2][l];
        ++iterations[l];
        const double rn2 = r0 * r0 + r1 * r1 + r2 * r2;
        if (rn2 <= tol2) {
          residual[l] = rn2;  // (squared) the exact residual at the returned point
          state[l] = done;
          continue;
        }
        if (rn2 > 0.25 * residual[l]) {  // |r| > ½ |r_previous| (residual holds squares)
          if (fresh[l]) {
            state[l] = failed;  // solve_point would switch to finite-difference Newton here
            continue;
          }
          have_step[l] = false;  // the next evaluation computes the step matrix at the iterate
        }
        residual[l] = rn2;
        if (iterations[l] >= max_iterations) {
          state[l] = failed;
          continue;
        }
        double s0 = S[0][l] * r0 + S[1][l] * r1 + S[2][l] * r2;
        double s1 = S[3][l] * r0 + S[4][l] * r1 + S[5][l] * r2;
        double s2 = S[6][l] * r0 + S[7][l] * r1 + S[8][l] * r2;
        if (second[l]) {
          // Second-order step from the same evaluation: with the step d = −s of the linear model, the
          // residual left at P + d is ≈ ½ H[d, d] (curvature of the error functions and the Abbe arms'
          // growth; ~1e-8 mm on Yang & Kweon's HMC); subtract (I + J)⁻¹ ½ H[d, d] as well. Only a better
          // start: the next evaluation checks the residual exactly as before.
          const double d[3] = {-s0, -s1, -s2};
          const double(&cv)[18][machine::batch_lanes] = data.lane_curvature;
          double h[3] = {0.0, 0.0, 0.0};
          for (int k = 0; k < 3; ++k) {
            double w[3];
            for (int m = 0; m < 3; ++m) w[m] = grows[m][k] ? d[m] : 0.0;
            const double a0 = cv[9 + 3 * k][l], a1 = cv[10 + 3 * k][l], a2 = cv[11 + 3 * k][l];
            const double dk2 = d[k] * d[k], tk = 2.0 * d[k];
            h[0] += dk2 * cv[3 * k][l] + tk * (a1 * w[2] - a2 * w[1]);
            h[1] += dk2 * cv[3 * k + 1][l] + tk * (a2 * w[0] - a0 * w[2]);
            h[2] += dk2 * cv[3 * k + 2][l] + tk * (a0 * w[1] - a1 * w[0]);
          }
          s0 += 0.5 * (S[0][l] * h[0] + S[1][l] * h[1] + S[2][l] * h[2]);
          s1 += 0.5 * (S[3][l] * h[0] + S[4][l] * h[1] + S[5][l] * h[2]);
          s2 += 0.5 * (S[6][l] * h[0] + S[7][l] * h[1] + S[8][l] * h[2]);
        }
        const double q0 = P[0][l] - s0;
        const double q1 = P[1][l] - s1;
        const double q2 = P[2][l] - s2;
        if (!std::isfinite(q0 + q1 + q2)) {  // (an overflowing sum only sends the point to the fallback)
          state[l] = failed;
          continue;
        }
        P[0][l] = q0, P[1][l] = q1, P[2][l] = q2;
        ++still;
      }
      if (still == 0) break;
    }
    // results of the block
    for (int l = 0; l < lanes; ++l) {
      if (state[l] == idle) continue;
      const Eigen::Index i = index[l];
      if (state[l] == failed) {
        again.push_back(i);
        have_prev[l] = have_matrix[l] = false;
        continue;
      }
      if (computed[l]) {
        for (int c = 0; c < 3; ++c) step_at[c][l] = N[c][l];
        have_matrix[l] = true;
      } else if (!have_step[l]) {
        have_matrix[l] = false;
      }
      VolumetricStatus st = VolumetricStatus::ok;
      int ax = -1;
      if (options.check_travel) {
        for (int k = 0; k < 3; ++k) {
          if (P[k][l] < travel_min[k] || P[k][l] > travel_max[k]) {
            ax = k;
            st = VolumetricStatus::outside_travel;
            break;
          }
        }
      }
      for (int c = 0; c < 3; ++c) res.commanded(i, c) = P[c][l];
      res.residual[i] = std::sqrt(residual[l]);
      res.iterations[i] = iterations[l];
      res.axis[i] = ax;
      res.status[static_cast<std::size_t>(i)] = st;
      have_prev[l] = st == VolumetricStatus::ok;
      for (int c = 0; c < 3; ++c) {
        prev_correction[c][l] = P[c][l] - N[c][l];
        prev_nominal[c][l] = N[c][l];
      }
    }
  }
  for (const Eigen::Index i : again) {
    Vec3 cmd;
    double r;
    int it, ax;
    res.status[static_cast<std::size_t>(i)] =
        compensate_point(machine, data, nominal.row(i).transpose(), options, cmd, r, it, ax);
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
