#pragma once
// Private: the deflection and wall-error limits of one force sample of a flat end mill, from the
// surface-generation model of netshape::deflection (docs/feeds.md, "Deflection and wall error").
#include <limits>

#include "netshape/compensation/feed_schedule.hpp"
#include "netshape/deflection/wall.hpp"
#include "netshape/stock/engagement.hpp"

namespace netshape::compensation::detail {

/// Largest c ≥ 0 with max_k |w ⊙ (c^p P_k + c^q Q_k)| ≤ limit (feed_samples.cpp).
double largest_feed_per_tooth(const Points3& P, const Points3& Q, double p, double q, const Vec3& w,
                              double limit);

/// Largest c ≥ 0 with peak(c) ≤ limit for a peak that grows with c: doubling from 1e-4 mm, then
/// 60 bisections; 0 when even 1e-4 exceeds it, inf when c passes 1e3 mm [mm/tooth].
template <typename Peak>
double largest_below(Peak peak, double limit) {
  double lo = 0.0, hi = 1e-4;
  while (peak(hi) <= limit) {
    lo = hi;
    hi *= 2.0;
    if (hi > 1e3) return std::numeric_limits<double>::infinity();
  }
  for (int it = 0; it < 60; ++it) {
    const double mid = 0.5 * (lo + hi);
    (peak(mid) <= limit ? lo : hi) = mid;
  }
  return lo;
}

/// The deflection model of a flat end mill as `netshape deflection` builds it from the cutter
/// (deflection::DeflectionModel: cantilever of the square section over the stick-out, distributed
/// load, smooth element edges, the cutter's holder compliance and runout), read at a sample with
/// the Z-map's engagement (stock::immersion: the window and the axial depth).
///   tip deflection  max_θ |δ(z = 0; θ)| over the rotation angles
///   wall error      max |e(z)| over the bottom, middle and top of the cut (deflection::cut_levels)
///                   on each wall the sample generates (bit 1 left, bit 2 right), e as wall.hpp
/// Without runout both are linear in the feed per tooth c (δ = c·δ_cut + δ_edge, the chip
/// h = c·max(sin φ, 0)): the tip's largest c from the quadratic per angle, the wall's from
/// |c·a + b| ≤ limit per level. With runout (chips clamped per flute) by bisection on c.
class SampleDeflection {
 public:
  SampleDeflection(const cutter::Cutter& cutter, const force::LinearEdgeCoefficients& k, double disk_height,
                   const VectorXd& angles);

  struct Result {
    double deflection_c = std::numeric_limits<double>::infinity();  ///< largest c the tip limit allows [mm]
    double wall_c = std::numeric_limits<double>::infinity();        ///< largest c the wall limit allows [mm]
    double deflection = 0.0;  ///< tip deflection at c0 [mm]
    double wall_error = 0.0;  ///< largest |wall error| at c0 [mm] (0 without a generated wall)
  };

  /// At `tip` moving along `direction` (unit, horizontal) through `stock` with walls `walls`, the
  /// programmed feed per tooth c0 [mm] and the limits [mm] (inf: not stated, its c stays inf).
  Result evaluate(const stock::ZMap& stock, const Vec3& tip, const Vec3& direction, int walls, double c0,
                  double max_deflection, double max_wall_error);

 private:
  double tip_peak(double c);
  double wall_peak(double c, int walls);
  void tip_parts();

  const cutter::Cutter& cutter_;
  deflection::DeflectionModel model_;
  deflection::DeflectionWorkspace ws_;
  force::LinearEdgeCoefficients full_, cut_, edge_;
  VectorXd angles_;
  Points3 P_, Q_;
};

}  // namespace netshape::compensation::detail
