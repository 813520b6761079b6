#pragma once
/// \file options.hpp
/// How the planner treats corners, its look-ahead depth and the two loop periods.

#include <cstdint>
#include <string>

namespace netshape::motion {

/// Corner (junction) rule between two blocks whose tangents differ.
///  - paper:   Lee & Lee eq. 4, F = Acc·Ts1/(1 − cos θ), floored by the allowable speed difference
///             (θ = turn angle). Velocity jumps at the vertex; the normal part is ignored.
///  - vector:  the whole velocity vector may jump by at most Acc·Ts2: 2F·sin(θ/2) ≤ Acc·Ts2.
///  - per_axis: each axis' velocity may jump by at most its own A_i·Ts2: F·|u2_i − u1_i| ≤ A_i·Ts2.
///  - junction_deviation: grbl / Klipper, v² = a·δ·cos(φ/2)/(1 − cos(φ/2)) at a turn φ between the
///             unit tangents (∞ straight on, 0 at a reversal), capped by both blocks' nominal speeds;
///             δ from `junction_deviation` or, when `square_corner_velocity` > 0, Klipper's mapping
///             δ = scv²·(√2 − 1)/a (a the smallest moving-axis limit); `a` per `junction_accel`.
///  - blend:   a G2 cubic Bézier blend replaces each corner within the contour tolerance; no jump.
enum class CornerRule : std::uint8_t { paper = 0, vector = 1, per_axis = 2, junction_deviation = 3, blend = 4 };

/// The acceleration of the junction-deviation rule at a corner u1 → u2:
///  - min_moving_axis: the smallest acceleration limit of the axes that move along u1 or u2;
///  - along_change: grbl's, the largest acceleration along the velocity change unit(u2 − u1) that
///    keeps every axis within its limit, min_i A_i/|e_i| (grbl's limit_value_by_axis_maximum).
enum class JunctionAccel : std::uint8_t { min_moving_axis = 0, along_change = 1 };

/// "min-moving-axis", "along-change" (the CLI spelling).
const char* junction_accel_name(JunctionAccel mode) noexcept;
/// Inverse of junction_accel_name; also accepts underscores. Throws std::invalid_argument on unknown names.
JunctionAccel parse_junction_accel(const std::string& name);

/// "paper", "vector", "per-axis", "junction-deviation", "blend" (the CLI spelling).
const char* rule_name(CornerRule rule) noexcept;
/// Inverse of rule_name; also accepts underscores. Throws std::invalid_argument on unknown names.
CornerRule parse_rule(const std::string& name);

/// Smallest blend / smoothing tolerance [mm] (1 nm): below it a blend is numerically a sharp corner.
inline constexpr double min_tolerance = 1e-6;

/// Planner options. Plain value type; `validate()` checks it.
struct PlanOptions {
  CornerRule rule = CornerRule::vector;
  double ts1 = 1e-3;   ///< rough loop period [s] (look-ahead and per-period displacement)
  double ts2 = 1e-4;   ///< fine loop period [s]; ts1 must be an integer multiple of ts2
  int lookahead = 64;  ///< look-ahead depth: segments held in the planner's ring buffer (>= 2)
  /// paper rule: allowable speed difference, the floor of the eq. 4 corner speed [mm/s]
  double allowable_speed_difference = 100.0 / 60.0;
  double tolerance = 0.01;              ///< blend rule: contour tolerance ε [mm]
  /// blend rule: contour tolerance at a vertex where neither block is a cubic block (programmed
  /// lines and arcs) [mm]; 0: `tolerance`. Rule smooth plans with tolerance (1 − fit_share)·ε next
  /// to its cubic blocks, which already use fit_share·ε, and the whole ε here.
  double corner_tolerance = 0.0;
  double junction_deviation = 0.0;      ///< junction-deviation rule: δ [mm] (used when scv = 0)
  double square_corner_velocity = 5.0;  ///< Klipper's square corner velocity [mm/s] (0: use δ)
  /// junction-deviation rule: which acceleration the corner speed uses (see JunctionAccel)
  JunctionAccel junction_accel = JunctionAccel::min_moving_axis;
  /// With jerk limits only: on arcs and blends, the share of the acceleration budget given to the
  /// centripetal part (v²κ ≤ c·A); the tangential part gets √(1 − c²)·A so that the vector sum stays
  /// ≤ A. Without jerk limits curves are planned against the per-axis box (docs/motion.md).
  double centripetal_fraction = 0.8;

  void validate() const;
  /// Number of fine periods per rough period, round(ts1/ts2).
  int fine_steps() const noexcept;
};

}  // namespace netshape::motion
