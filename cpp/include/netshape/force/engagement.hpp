#pragma once
/// \file engagement.hpp
/// Which cutter elements cut: an angular window [φ_st, φ_ex] from the milling mode and the radial
/// depth (docs/conventions.md §2), or a per-disk map of angular bins in material (from a Z-map,
/// Kim et al. §3.2).

#include <cstdint>
#include <string>

#include "netshape/core/types.hpp"

namespace netshape::force {

enum class MillingMode : std::uint8_t { up = 0, down = 1, slot = 2 };
const char* to_string(MillingMode m) noexcept;
/// "up", "down" or "slot"; throws std::invalid_argument otherwise.
MillingMode milling_mode_from_string(const std::string& s);

/// Angular window in which an element cuts, immersion angles measured clockwise from +Y seen from
/// the spindle (docs/conventions.md §2). An element at immersion φ cuts if φ (mod 2π) ∈ [phi_st, phi_ex].
struct AngularEngagement {
  double phi_st = 0.0;  ///< start (entry) angle [rad], in [0, 2π)
  double phi_ex = pi;   ///< exit angle [rad], phi_st < phi_ex ≤ phi_st + 2π
  void validate() const;
  /// Up milling: [0, acos(1 − a_e/R)]; down milling: [π − acos(1 − a_e/R), π]; slot: [0, π]
  /// (a_e is ignored for slot). radius R [mm] > 0 is the tool's largest radius, radial_depth a_e [mm]
  /// in (0, 2R] is measured from the wall to that radius (the wall is at R − a_e from the axis).
  /// The window is the one of an element at radius R; BallEndModel reads it as the wall and gives an
  /// element of radius r < R its own, narrower window.
  static AngularEngagement from_mode(MillingMode mode, double radius, double radial_depth);
};

/// Engagement from material: for every disk i of a model and every angular bin b of width 2π/bins
/// (bin b covers immersion angles [b, b+1)·2π/bins), whether material lies at the element's place.
/// Filled by a Z-map query (netshape::stock) or from an AngularEngagement for comparison.
/// mask is (disks, bins) row-major, 0 or 1.
struct EngagementMap {
  Eigen::Matrix<std::uint8_t, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor> mask;
  int bins() const noexcept { return static_cast<int>(mask.cols()); }
  int disks() const noexcept { return static_cast<int>(mask.rows()); }
  /// Every disk gets the bins whose centre lies in the window.
  static EngagementMap from_window(const AngularEngagement& window, int disks, int bins);
};

}  // namespace netshape::force
