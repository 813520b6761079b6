#include "netshape/geometry/cutter_location.hpp"

#include <algorithm>
#include <cmath>

#include "netshape/core/error.hpp"

namespace netshape::geometry {

namespace {
struct Profile {
  double R, r;
};
Profile profile_of(const cutter::Cutter& c) {
  c.validate();
  switch (c.kind) {
    case cutter::CutterKind::ball:
      return {c.radius, c.radius};
    case cutter::CutterKind::bull:
      return {c.radius, c.corner_radius};
    case cutter::CutterKind::flat:
    default:
      return {c.radius, 0.0};
  }
}

Vec3 unit_axis(const Vec3& axis) {
  for (int i = 0; i < 3; ++i) NETSHAPE_CHECK_FINITE("axis", axis[i]);
  const double n = axis.norm();
  NETSHAPE_CHECK(n > 1e-300, "axis", n, "tool axis must be a non-zero vector");
  return axis / n;
}

inline Vec3 one(const Profile& pr, const Vec3& cc, const Vec3& normal, const Vec3& a) {
  const double nn = normal.norm();
  NETSHAPE_CHECK(std::isfinite(nn) && nn > 1e-300, "normal", nn, "surface normal must be finite and non-zero");
  for (int i = 0; i < 3; ++i) NETSHAPE_CHECK_FINITE("cc", cc[i]);
  const Vec3 n = normal / nn;
  const double na = n.dot(a);
  NETSHAPE_CHECK(na >= -1e-12, "normal . axis", na,
                 "surface normal faces away from the tool axis: the cutter cannot reach this CC point");
  const Vec3 h = n - na * a;
  const double hn = h.norm();
  const Vec3 e = (hn > 1e-12) ? Vec3(h / hn) : Vec3::Zero();
  return cc + pr.r * n + (pr.R - pr.r) * e - pr.r * a;
}
}  // namespace

Vec3 cc_to_cl(const cutter::Cutter& cutter, const Vec3& cc, const Vec3& normal, const Vec3& axis) {
  return one(profile_of(cutter), cc, normal, unit_axis(axis));
}

void cc_to_cl(const cutter::Cutter& cutter, const Eigen::Ref<const Points3>& cc,
              const Eigen::Ref<const Points3>& normals, const Vec3& axis, Eigen::Ref<Points3> out) {
  NETSHAPE_CHECK(normals.rows() == cc.rows(), "normals.rows", normals.rows(), "must equal cc.rows");
  NETSHAPE_CHECK(out.rows() == cc.rows(), "out.rows", out.rows(), "must equal cc.rows");
  const Profile pr = profile_of(cutter);
  const Vec3 a = unit_axis(axis);
  for (Eigen::Index k = 0; k < cc.rows(); ++k)
    out.row(k) = one(pr, cc.row(k).transpose(), normals.row(k).transpose(), a).transpose();
}

VectorXd cutter_signed_distance(const cutter::Cutter& cutter, const Vec3& tip, const Vec3& axis,
                                const Eigen::Ref<const Points3>& points) {
  // The solid is K ⊕ ball(r) with K = {tip + (r + t) a + w : t ≥ 0, w ⟂ a, |w| ≤ R − r} (convex), so its
  // signed distance is dist_K − r, computed in the (radial ρ, height h) half-plane.
  const Profile pr = profile_of(cutter);
  const Vec3 a = unit_axis(axis);
  for (int i = 0; i < 3; ++i) NETSHAPE_CHECK_FINITE("tip", tip[i]);
  const double rk = pr.R - pr.r;
  VectorXd out(points.rows());
  for (Eigen::Index k = 0; k < points.rows(); ++k) {
    const Vec3 d = points.row(k).transpose() - tip;
    const double h = d.dot(a);
    const double rho = (d - h * a).norm();
    const double dx = rho - rk, dy = pr.r - h;  // outside K if dx > 0 or dy > 0
    double dk;
    if (dx <= 0 && dy <= 0)
      dk = std::max(dx, dy);  // inside K: minus the depth
    else
      dk = std::hypot(std::max(dx, 0.0), std::max(dy, 0.0));
    out[k] = dk - pr.r;
  }
  return out;
}

}  // namespace netshape::geometry
