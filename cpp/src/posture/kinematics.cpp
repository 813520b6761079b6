// Inverse and forward kinematics of table-tilting A/C and head-tilting B/C machines.
#include "netshape/posture/kinematics.hpp"

#include <cmath>
#include <string>

#include "netshape/core/error.hpp"

namespace netshape::posture {

void Kinematics::validate() const {
  NETSHAPE_CHECK(table_centre.allFinite(), "table_centre", table_centre.transpose(), "must be finite [mm]");
  NETSHAPE_CHECK(std::isfinite(pivot_length) && pivot_length >= 0, "pivot_length", pivot_length, "must be ≥ 0 [mm]");
  NETSHAPE_CHECK(std::isfinite(tilt_min) && tilt_min >= -pi, "tilt_min", tilt_min, "must be in [−π, tilt_max) [rad]");
  NETSHAPE_CHECK(std::isfinite(tilt_max) && tilt_max <= pi && tilt_max > tilt_min, "tilt_max", tilt_max,
                 "must be in (tilt_min, π] [rad]");
}

namespace {
Mat3 rot_x(double a) { return Eigen::AngleAxisd(a, Vec3::UnitX()).toRotationMatrix(); }
Mat3 rot_y(double a) { return Eigen::AngleAxisd(a, Vec3::UnitY()).toRotationMatrix(); }
Mat3 rot_z(double a) { return Eigen::AngleAxisd(a, Vec3::UnitZ()).toRotationMatrix(); }

// c + 2πk nearest to ref
double unwrap_near(double c, double ref) { return c + 2.0 * pi * std::round((ref - c) / (2.0 * pi)); }
}  // namespace

MatrixXdR inverse_kinematics(const Kinematics& kin, const Eigen::Ref<const Points3>& tips,
                             const Eigen::Ref<const Points3>& axes, double c_start) {
  kin.validate();
  NETSHAPE_CHECK(tips.rows() == axes.rows(), "axes.rows", axes.rows(), "must equal tips.rows");
  NETSHAPE_CHECK(std::isfinite(c_start), "c_start", c_start, "must be finite [rad]");
  const Eigen::Index n = tips.rows();
  MatrixXdR out(n, 5);
  double tilt_prev = 0.0, c_prev = c_start;
  const double sing = 1e-9;
  for (Eigen::Index i = 0; i < n; ++i) {
    const std::string field = "point " + std::to_string(i);
    NETSHAPE_CHECK(tips.row(i).allFinite(), field.c_str(), tips.row(i), "tip must be finite [mm]");
    Vec3 a = axes.row(i).transpose();
    const double len = a.norm();
    NETSHAPE_CHECK(std::isfinite(len) && len > 0, field.c_str(), axes.row(i), "axis must be a non-zero vector");
    a /= len;
    const double rho = std::hypot(a.x(), a.y());
    const double tilt = std::atan2(rho, a.z());  // ≥ 0
    double c1;
    if (rho < sing) {
      c1 = c_prev;  // singular: any C; keep the previous one
    } else if (kin.kind == MachineKind::table_ac) {
      c1 = std::atan2(a.x(), a.y());  // a = (sin A sin C, sin A cos C, cos A)
    } else {
      c1 = std::atan2(a.y(), a.x());  // a = (sin B cos C, sin B sin C, cos B)
    }
    // the two branches, C unwrapped next to the previous C
    const double cand_t[2] = {tilt, -tilt};
    const double cand_c[2] = {unwrap_near(c1, c_prev), unwrap_near(c1 + pi, c_prev)};
    int pick = -1;
    double best = 0.0;
    for (int b = 0; b < (rho < sing ? 1 : 2); ++b) {
      if (cand_t[b] < kin.tilt_min - 1e-12 || cand_t[b] > kin.tilt_max + 1e-12) continue;
      const double cost = std::abs(cand_t[b] - tilt_prev) + std::abs(cand_c[b] - c_prev);
      if (pick < 0 || cost < best) {
        pick = b;
        best = cost;
      }
    }
    if (pick < 0) {
      std::ostringstream os;
      os << "axis (" << a.transpose() << ") needs tilt ±" << rad2deg(tilt) << " deg, outside the limits ["
         << rad2deg(kin.tilt_min) << ", " << rad2deg(kin.tilt_max) << "] deg";
      throw std::invalid_argument(field + ": " + os.str());
    }
    const double t = cand_t[pick], c = rho < sing ? c_prev : cand_c[pick];
    const Vec3 tip = tips.row(i).transpose();
    Vec3 x;
    if (kin.kind == MachineKind::table_ac) {
      x = kin.table_centre + rot_x(t) * rot_z(c) * tip;
    } else {
      x = tip + kin.pivot_length * a;
    }
    out.row(i) << x.x(), x.y(), x.z(), t, c;
    tilt_prev = t;
    c_prev = c;
  }
  return out;
}

void forward_kinematics(const Kinematics& kin, const Eigen::Ref<const MatrixXdR>& joints, Points3& tips,
                        Points3& axes) {
  kin.validate();
  NETSHAPE_CHECK(joints.cols() == 5, "joints.cols", joints.cols(), "must be 5 (X, Y, Z, tilt, C)");
  const Eigen::Index n = joints.rows();
  tips.resize(n, 3);
  axes.resize(n, 3);
  for (Eigen::Index i = 0; i < n; ++i) {
    NETSHAPE_CHECK(joints.row(i).allFinite(), "joints row", i, "must be finite");
    const Vec3 x(joints(i, 0), joints(i, 1), joints(i, 2));
    const double t = joints(i, 3), c = joints(i, 4);
    if (kin.kind == MachineKind::table_ac) {
      const Mat3 inv = (rot_x(t) * rot_z(c)).transpose();
      tips.row(i) = (inv * (x - kin.table_centre)).transpose();
      axes.row(i) = (inv * Vec3::UnitZ()).transpose();
    } else {
      const Vec3 a = rot_z(c) * rot_y(t) * Vec3::UnitZ();
      axes.row(i) = a.transpose();
      tips.row(i) = (x - kin.pivot_length * a).transpose();
    }
  }
}

}  // namespace netshape::posture
