// MB-spline spans, joins and the smoothing of posture-vector end points.
#include "netshape/posture/mb_spline.hpp"

#include <cmath>

#include "netshape/core/error.hpp"

namespace netshape::posture {

namespace {
void check_span(const Eigen::Ref<const Points3>& c, int span, double u) {
  NETSHAPE_CHECK(c.rows() >= 4, "control.rows", c.rows(), "an MB-spline needs at least 4 control points");
  NETSHAPE_CHECK(c.allFinite(), "control", "non-finite", "control points must be finite [mm]");
  NETSHAPE_CHECK(span >= 0 && span <= c.rows() - 4, "span", span, "must be in [0, n − 4]");
  NETSHAPE_CHECK(std::isfinite(u) && u >= 0.0 && u <= 1.0, "u", u, "must be in [0, 1]");
}
}  // namespace

Vec3 mb_spline_point(const Eigen::Ref<const Points3>& c, int span, double u) {
  check_span(c, span, u);
  // [1 u u²]·M/4: weights of P_i … P_{i+3}
  const double w0 = (1.0 - 2.0 * u + u * u) / 4.0;
  const double w1 = (2.0 - u * u) / 4.0;
  const double w2 = (1.0 + 2.0 * u - u * u) / 4.0;
  const double w3 = (u * u) / 4.0;
  return (w0 * c.row(span) + w1 * c.row(span + 1) + w2 * c.row(span + 2) + w3 * c.row(span + 3)).transpose();
}

Vec3 mb_spline_derivative(const Eigen::Ref<const Points3>& c, int span, double u) {
  check_span(c, span, u);
  const double w0 = (-2.0 + 2.0 * u) / 4.0;
  const double w1 = (-2.0 * u) / 4.0;
  const double w2 = (2.0 - 2.0 * u) / 4.0;
  const double w3 = (2.0 * u) / 4.0;
  return (w0 * c.row(span) + w1 * c.row(span + 1) + w2 * c.row(span + 2) + w3 * c.row(span + 3)).transpose();
}

Points3 mb_spline_joins(const Eigen::Ref<const Points3>& c) {
  NETSHAPE_CHECK(c.rows() >= 3, "control.rows", c.rows(), "joins need at least 3 control points");
  Points3 out(c.rows() - 2, 3);
  for (Eigen::Index i = 0; i + 2 < c.rows(); ++i) out.row(i) = 0.25 * (c.row(i) + 2.0 * c.row(i + 1) + c.row(i + 2));
  return out;
}

Points3 mb_smooth(const Eigen::Ref<const Points3>& points, int passes) {
  NETSHAPE_CHECK(passes >= 0, "passes", passes, "must be ≥ 0");
  NETSHAPE_CHECK(points.allFinite(), "points", "non-finite", "points must be finite [mm]");
  Points3 p = points;
  const Eigen::Index n = p.rows();
  if (n < 3) return p;
  Points3 ext(n + 2, 3);
  for (int k = 0; k < passes; ++k) {
    ext.middleRows(1, n) = p;
    ext.row(0) = 2.0 * p.row(0) - p.row(1);
    ext.row(n + 1) = 2.0 * p.row(n - 1) - p.row(n - 2);
    p = mb_spline_joins(ext);
  }
  return p;
}

}  // namespace netshape::posture
