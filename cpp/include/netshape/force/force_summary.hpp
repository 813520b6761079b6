#pragma once
/// \file force_summary.hpp
/// Per-revolution statistics of a force series: mean, peak and resultant.

#include <vector>

#include "netshape/core/types.hpp"

namespace netshape::force {

struct ForceSummary {
  Vec3 mean = Vec3::Zero();        ///< mean (Fx, Fy, Fz) over the revolution [N]
  Vec3 peak = Vec3::Zero();        ///< largest |Fx|, |Fy|, |Fz| [N]
  double peak_resultant = 0.0;     ///< max √(Fx²+Fy²+Fz²) [N]
  double mean_resultant = 0.0;     ///< mean √(Fx²+Fy²+Fz²) [N]
  double peak_resultant_xy = 0.0;  ///< max √(Fx²+Fy²) [N]
};

/// |F| per sample, (n) [N].
VectorXd resultant(const Eigen::Ref<const Points3>& forces);

/// Statistics over all samples (take them uniformly over whole revolutions).
ForceSummary summarize(const Eigen::Ref<const Points3>& forces);

/// One summary per whole revolution: samples are grouped by floor((θ − θ0)/2π) with θ0 = angles[0];
/// angles (n) [rad] must be increasing; a trailing partial revolution is dropped (at least one whole
/// revolution is required).
std::vector<ForceSummary> summarize_revolutions(const Eigen::Ref<const VectorXd>& angles,
                                                const Eigen::Ref<const Points3>& forces);

}  // namespace netshape::force
