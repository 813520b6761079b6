// NurbsSurface point projection (netshape/geometry/nurbs_surface.hpp): closest points by a grid search
// then a bounded Newton iteration on the surface parameters.
#include "netshape/geometry/nurbs_surface.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include "netshape/core/error.hpp"
#include "netshape/geometry/basis.hpp"

namespace netshape::geometry {

namespace {
struct ProjectionGrid {
  VectorXd us, vs;
  Points3 pts;
};
}  // namespace

static ProjectionGrid projection_grid(const NurbsSurface& s) {
  const auto [ua, ub] = s.domain_u();
  const auto [va, vb] = s.domain_v();
  const int na = std::max(12, 3 * s.count_u() * s.degree_u()), nb = std::max(12, 3 * s.count_v() * s.degree_v());
  ProjectionGrid g;
  g.us = VectorXd::LinSpaced(na, ua, ub);
  g.vs = VectorXd::LinSpaced(nb, va, vb);
  SurfaceWorkspace ws = s.make_workspace();
  g.pts.resize(static_cast<Eigen::Index>(na) * nb, 3);
  Points3 none(0, 3);
  s.evaluate_grid(g.us, g.vs, g.pts, none, ws);
  return g;
}

SurfaceProjection NurbsSurface::closest_point(const Vec3& p, double tolerance, int max_iterations) const {
  return closest_points(p.transpose(), tolerance, max_iterations).front();
}

std::vector<SurfaceProjection> NurbsSurface::closest_points(const Eigen::Ref<const Points3>& points, double tolerance,
                                                            int max_iterations) const {
  NETSHAPE_CHECK(tolerance > 0.0, "tolerance", tolerance, "must be positive [mm]");
  NETSHAPE_CHECK(max_iterations >= 1, "max_iterations", max_iterations, "must be at least 1");
  for (Eigen::Index k = 0; k < points.rows(); ++k)
    for (int c = 0; c < 3; ++c) NETSHAPE_CHECK_FINITE("point", points(k, c));
  const ProjectionGrid grid = projection_grid(*this);
  std::vector<SurfaceProjection> out;
  out.reserve(points.rows());
  std::vector<std::pair<double, Eigen::Index>> order(grid.pts.rows());
  for (Eigen::Index q = 0; q < points.rows(); ++q)
    out.push_back(project_from_grid(points.row(q).transpose(), grid.us, grid.vs, grid.pts, order, tolerance,
                                    max_iterations));
  return out;
}

SurfaceProjection NurbsSurface::project_from_grid(const Vec3& p, const VectorXd& us, const VectorXd& vs,
                                                  const Points3& pts,
                                                  std::vector<std::pair<double, Eigen::Index>>& order,
                                                  double tolerance, int max_iterations) const {
  const auto [ua, ub] = domain_u();
  const auto [va, vb] = domain_v();
  const Eigen::Index nb = vs.size();
  for (Eigen::Index k = 0; k < pts.rows(); ++k) order[k] = {(pts.row(k).transpose() - p).squaredNorm(), k};
  const int starts = static_cast<int>(std::min<std::size_t>(4, order.size()));
  std::partial_sort(order.begin(), order.begin() + starts, order.end());
  SurfaceProjection best;
  best.distance = std::numeric_limits<double>::infinity();
  for (int st = 0; st < starts; ++st) {
    double u = us[order[st].second / nb], v = vs[order[st].second % nb];
    SurfaceProjection r;
    for (int it = 0; it < max_iterations; ++it) {
      r.iterations = it + 1;
      const MatrixXdR d = derivatives(u, v, 2);  // D = 3: row k·3 + l
      const Vec3 S = d.row(0).transpose(), Su = d.row(3).transpose(), Sv = d.row(1).transpose();
      const Vec3 Suu = d.row(6).transpose(), Suv = d.row(4).transpose(), Svv = d.row(2).transpose();
      const Vec3 rr = S - p;
      if (rr.norm() <= tolerance) {
        r.converged = true;
        break;
      }
      const double f = Su.dot(rr), g = Sv.dot(rr);
      if (std::abs(f) <= 1e-14 * Su.norm() * rr.norm() + 1e-300 &&
          std::abs(g) <= 1e-14 * Sv.norm() * rr.norm() + 1e-300) {
        r.converged = true;
        break;
      }
      Eigen::Matrix2d J;
      J << Su.squaredNorm() + rr.dot(Suu), Su.dot(Sv) + rr.dot(Suv), Su.dot(Sv) + rr.dot(Suv),
          Sv.squaredNorm() + rr.dot(Svv);
      Eigen::Vector2d step;
      const Eigen::Vector2d rhs(-f, -g);
      if (J.determinant() > 1e-300 && J(0, 0) > 0) {
        step = J.ldlt().solve(rhs);
      } else {  // not a descent Hessian: Gauss-Newton step
        Eigen::Matrix2d G;
        G << Su.squaredNorm(), Su.dot(Sv), Su.dot(Sv), Sv.squaredNorm();
        G.diagonal().array() += 1e-12 * (G.trace() + 1e-300);
        step = G.ldlt().solve(rhs);
      }
      const double un = std::clamp(u + step[0], ua, ub), vn = std::clamp(v + step[1], va, vb);
      const double moved = ((un - u) * Su + (vn - v) * Sv).norm();
      u = un;
      v = vn;
      if (moved <= tolerance) {
        r.converged = true;
        break;
      }
    }
    r.u = u;
    r.v = v;
    r.point = point(u, v);
    r.distance = (r.point - p).norm();
    if (r.distance < best.distance) best = r;
  }
  best.normal = normal(best.u, best.v);
  return best;
}

}  // namespace netshape::geometry
