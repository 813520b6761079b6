#pragma once
/// \file tip_profile.hpp
/// The lower surface of a 3-axis end mill as a function of the horizontal distance from its axis.
///
/// A flat, ball or bull-nose end mill is a disc of radius a = R − r_c (flat: r_c = 0, ball: a = 0)
/// Minkowski-summed with a ball of radius r_c whose centre sits r_c above the tip. Its lowest point
/// at horizontal distance d ≤ R from the axis lies
///
///     g(d) = 0                                  for d ≤ a
///     g(d) = r_c − sqrt(r_c² − (d − a)²)        for a < d ≤ R            [mm above the tip]
///
/// g is convex and non-decreasing on [0, R], which is what makes the line sweep a convex 1-D problem.

#include <cmath>
#include <limits>

#include "netshape/cutter/cutter.hpp"

namespace netshape::stock {

struct TipProfile {
  double radius = 5.0;         ///< R [mm]
  double corner_radius = 0.0;  ///< r_c [mm]
  double flat_radius = 5.0;    ///< a = R − r_c [mm]

  /// Profile of a validated cutter.
  static TipProfile of(const cutter::Cutter& c) noexcept {
    TipProfile p;
    p.radius = c.radius;
    p.corner_radius = c.kind == cutter::CutterKind::flat ? 0.0 : c.corner_radius;
    p.flat_radius = p.radius - p.corner_radius;
    return p;
  }
  /// g(d): height of the lower surface above the tip at horizontal distance d [mm]; valid for
  /// 0 ≤ d ≤ R (beyond R returns +inf: the cutter does not reach there).
  double lift(double d) const noexcept {
    if (d <= flat_radius) return 0.0;
    if (d > radius) return std::numeric_limits<double>::infinity();
    const double u = d - flat_radius;
    const double w = corner_radius * corner_radius - u * u;
    return corner_radius - std::sqrt(w > 0.0 ? w : 0.0);
  }
  /// g'(d) [-] (+inf at d = R for ball and bull).
  double slope(double d) const noexcept {
    if (d <= flat_radius) return 0.0;
    const double u = d - flat_radius;
    const double w = corner_radius * corner_radius - u * u;
    return w > 0.0 ? u / std::sqrt(w) : std::numeric_limits<double>::infinity();
  }
};

}  // namespace netshape::stock
