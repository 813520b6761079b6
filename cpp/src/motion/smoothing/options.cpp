// SmoothOptions::validate() (netshape/motion/smoothing.hpp).
#include <cmath>

#include "netshape/core/error.hpp"
#include "netshape/motion/options.hpp"
#include "netshape/motion/smoothing.hpp"

namespace netshape::motion {

void SmoothOptions::validate() const {
  NETSHAPE_CHECK(tolerance >= min_tolerance && std::isfinite(tolerance), "tolerance", tolerance,
                 "must be >= 1e-06 [mm]");
  NETSHAPE_CHECK(fit_share > 0 && fit_share < 1, "fit_share", fit_share, "must be in (0, 1)");
  NETSHAPE_CHECK(max_segment > 0 && std::isfinite(max_segment), "max_segment", max_segment, "must be positive [mm]");
  NETSHAPE_CHECK(max_turn > 0 && max_turn < pi, "max_turn", max_turn, "must be in (0, pi) [rad]");
  NETSHAPE_CHECK(max_fit_turn >= 0 && max_fit_turn < pi, "max_fit_turn", max_fit_turn, "must be in [0, pi) [rad]");
  NETSHAPE_CHECK(min_blocks >= 2, "min_blocks", min_blocks, "must be >= 2");
  NETSHAPE_CHECK(window >= 8, "window", window, "must be >= 8 [blocks]");
  NETSHAPE_CHECK(max_refinements >= 1, "max_refinements", max_refinements, "must be >= 1");
  NETSHAPE_CHECK(smoothing_length >= 0 && std::isfinite(smoothing_length), "smoothing_length", smoothing_length,
                 "must be >= 0 [mm]");
  NETSHAPE_CHECK(knot_spacing > 0 && std::isfinite(knot_spacing), "knot_spacing", knot_spacing, "must be positive");
  NETSHAPE_CHECK(lead_length >= 0 && std::isfinite(lead_length), "lead_length", lead_length, "must be >= 0 [mm]");
  NETSHAPE_CHECK(plane_tolerance >= 0, "plane_tolerance", plane_tolerance, "must be >= 0 [mm]");
  NETSHAPE_CHECK(space_flatness >= 0 && space_flatness < 1, "space_flatness", space_flatness, "must be in [0, 1)");
}

}  // namespace netshape::motion
