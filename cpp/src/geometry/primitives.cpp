#include "netshape/geometry/primitives.hpp"

#include <algorithm>
#include <cmath>
#include <vector>

#include "netshape/core/error.hpp"

namespace netshape::geometry {

namespace {
struct ArcNet {
  std::vector<Vec3> points;   // 2·narcs + 1
  std::vector<double> weights;
  VectorXd knots;
};

ArcNet arc_net(const Vec3& O, const Vec3& X, const Vec3& Y, double r, double ths, double the) {
  const double theta = the - ths;
  const int narcs = std::max(1, static_cast<int>(std::ceil(theta / (0.5 * pi) - 1e-12)));
  const double dtheta = theta / narcs;
  const double w1 = std::cos(0.5 * dtheta);
  ArcNet net;
  net.points.resize(2 * narcs + 1);
  net.weights.resize(2 * narcs + 1);
  auto at = [&](double a, double rad) -> Vec3 { return O + rad * (std::cos(a) * X + std::sin(a) * Y); };
  net.points[0] = at(ths, r);
  net.weights[0] = 1.0;
  for (int i = 1; i <= narcs; ++i) {
    const double a0 = ths + (i - 1) * dtheta;
    net.points[2 * i - 1] = at(a0 + 0.5 * dtheta, r / w1);  // intersection of the end tangents
    net.weights[2 * i - 1] = w1;
    net.points[2 * i] = at(a0 + dtheta, r);
    net.weights[2 * i] = 1.0;
  }
  const int n = 2 * narcs + 1;
  net.knots.resize(n + 3);
  for (int i = 0; i < 3; ++i) {
    net.knots[i] = 0.0;
    net.knots[n + i] = 1.0;
  }
  for (int i = 1; i < narcs; ++i) net.knots[1 + 2 * i] = net.knots[2 + 2 * i] = static_cast<double>(i) / narcs;
  return net;
}

void check_vec(const char* field, const Vec3& v) {
  for (int c = 0; c < 3; ++c) NETSHAPE_CHECK_FINITE(field, v[c]);
}
}  // namespace

NurbsCurve circular_arc(const Vec3& center, const Vec3& x_axis, const Vec3& y_axis, double radius, double start,
                        double end) {
  check_vec("center", center);
  check_vec("x_axis", x_axis);
  check_vec("y_axis", y_axis);
  NETSHAPE_CHECK(std::isfinite(radius) && radius > 0, "radius", radius, "must be positive [mm]");
  NETSHAPE_CHECK(std::isfinite(start), "start", start, "must be finite [rad]");
  NETSHAPE_CHECK(std::isfinite(end) && end > start && end - start <= 2 * pi + 1e-12, "end", end,
                 "must satisfy start < end <= start + 2π [rad]");
  NETSHAPE_CHECK(x_axis.norm() > 0 && y_axis.norm() > 0 &&
                     std::abs(x_axis.normalized().dot(y_axis.normalized())) < 1e-9,
                 "y_axis", y_axis.norm(), "x_axis and y_axis must be non-zero and perpendicular");
  const ArcNet net = arc_net(center, x_axis.normalized(), y_axis.normalized(), radius, start, end);
  Points3 cp(net.points.size(), 3);
  VectorXd w(net.points.size());
  for (std::size_t i = 0; i < net.points.size(); ++i) {
    cp.row(i) = net.points[i].transpose();
    w[i] = net.weights[i];
  }
  return NurbsCurve(2, net.knots, cp, w);
}

NurbsSurface revolve(const NurbsCurve& profile, const Vec3& axis_point, const Vec3& axis_direction, double angle) {
  check_vec("axis_point", axis_point);
  check_vec("axis_direction", axis_direction);
  NETSHAPE_CHECK(axis_direction.norm() > 0, "axis_direction", axis_direction.norm(), "must be non-zero");
  NETSHAPE_CHECK(std::isfinite(angle) && angle > 0 && angle <= 2 * pi + 1e-12, "angle", angle,
                 "must be in (0, 2π] [rad]");
  const Vec3 a = axis_direction.normalized();
  const int n = profile.count();
  // reference direction for profile points on the axis: any perpendicular
  Vec3 ref = a.unitOrthogonal();
  ArcNet unit = arc_net(Vec3::Zero(), Vec3::UnitX(), Vec3::UnitY(), 1.0, 0.0, angle);
  const int m = static_cast<int>(unit.points.size());
  Points3 cp(static_cast<Eigen::Index>(n) * m, 3);
  VectorXd w(cp.rows());
  for (int i = 0; i < n; ++i) {
    const Vec3 P = profile.control_points().row(i).transpose();
    const Vec3 O = axis_point + a * a.dot(P - axis_point);
    Vec3 X = P - O;
    const double r = X.norm();
    X = (r > 1e-15 * std::max(1.0, P.norm())) ? Vec3(X / r) : ref;
    const Vec3 Y = a.cross(X);
    for (int j = 0; j < m; ++j) {
      const Vec3 c = unit.points[j];  // on the unit circle frame (x, y)
      cp.row(i * m + j) = (O + r * (c.x() * X + c.y() * Y)).transpose();
      w[i * m + j] = profile.weights()[i] * unit.weights[j];
    }
  }
  return NurbsSurface(profile.degree(), 2, profile.knots(), unit.knots, cp, w);
}

NurbsSurface bilinear(const Vec3& p00, const Vec3& p10, const Vec3& p01, const Vec3& p11) {
  Points3 cp(4, 3);
  cp.row(0) = p00.transpose();
  cp.row(1) = p01.transpose();
  cp.row(2) = p10.transpose();
  cp.row(3) = p11.transpose();
  VectorXd k(4);
  k << 0, 0, 1, 1;
  return NurbsSurface(1, 1, k, k, cp);
}

}  // namespace netshape::geometry
