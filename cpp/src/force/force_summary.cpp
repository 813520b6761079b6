#include "netshape/force/force_summary.hpp"

#include <cmath>

#include "netshape/core/error.hpp"

namespace netshape::force {

VectorXd resultant(const Eigen::Ref<const Points3>& forces) { return forces.rowwise().norm(); }

ForceSummary summarize(const Eigen::Ref<const Points3>& forces) {
  NETSHAPE_CHECK(forces.rows() >= 1, "forces.rows", forces.rows(), "must be at least 1");
  ForceSummary s;
  s.mean = forces.colwise().mean().transpose();
  s.peak = forces.cwiseAbs().colwise().maxCoeff().transpose();
  const VectorXd r = forces.rowwise().norm();
  s.peak_resultant = r.maxCoeff();
  s.mean_resultant = r.mean();
  s.peak_resultant_xy = forces.leftCols<2>().rowwise().norm().maxCoeff();
  return s;
}

std::vector<ForceSummary> summarize_revolutions(const Eigen::Ref<const VectorXd>& angles,
                                                const Eigen::Ref<const Points3>& forces) {
  const Eigen::Index n = angles.size();
  NETSHAPE_CHECK(forces.rows() == n, "forces.rows", forces.rows(), "must equal the number of angles");
  NETSHAPE_CHECK(n >= 2, "angles.size", n, "must be at least 2");
  for (Eigen::Index k = 0; k < n; ++k) NETSHAPE_CHECK_FINITE("angles", angles[k]);
  for (Eigen::Index k = 1; k < n; ++k)
    NETSHAPE_CHECK(angles[k] > angles[k - 1], "angles", angles[k], "must be increasing [rad]");
  const double two_pi = 2.0 * pi;
  const double step = (angles[n - 1] - angles[0]) / static_cast<double>(n - 1);
  const double end = angles[n - 1] + step;  // the samples cover [angles[0], end)
  const int whole = static_cast<int>(std::floor((end - angles[0]) / two_pi + 1e-9));
  NETSHAPE_CHECK(whole >= 1, "angles", angles[n - 1] - angles[0],
                 "must span at least one whole revolution [rad]");
  std::vector<ForceSummary> out;
  out.reserve(whole);
  Eigen::Index first = 0;
  for (int r = 0; r < whole; ++r) {
    const double hi = angles[0] + two_pi * (r + 1) - 1e-9 * step;
    Eigen::Index last = first;
    while (last < n && angles[last] < hi) ++last;
    if (last > first) out.push_back(summarize(forces.middleRows(first, last - first)));
    first = last;
  }
  return out;
}

}  // namespace netshape::force
