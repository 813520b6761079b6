#pragma once
/// \file block.hpp
/// One motion block of a machining program: rapid, line or (helical) arc, in absolute program
/// coordinates [mm] with the modal state that was in force when it was read.

#include <cstdint>

#include "netshape/core/types.hpp"

namespace netshape::toolpath {

/// Kind of motion. Values are stable (they are the dtype of NumPy `kind` arrays).
enum class MotionKind : std::uint8_t { rapid = 0, line = 1, arc = 2 };

/// Arc plane (G17, G18, G19). An arc turns about the plane's normal axis:
/// xy → +Z (axes a = X, b = Y), zx → +Y (a = Z, b = X), yz → +X (a = Y, b = Z).
/// "Clockwise" (G2) is seen looking from the positive normal axis towards the origin.
enum class Plane : std::uint8_t { xy = 0, zx = 1, yz = 2 };

/// Indices (a, b, normal) of a plane's in-plane axes and its normal axis into (x, y, z).
struct PlaneAxes {
  int a, b, n;
};
PlaneAxes plane_axes(Plane p) noexcept;

/// A motion block. Plain value type; `validate()` checks it.
struct Block {
  MotionKind kind = MotionKind::line;
  Vec3 start = Vec3::Zero();   ///< start point [mm]
  Vec3 end = Vec3::Zero();     ///< end point [mm]
  Vec3 center = Vec3::Zero();  ///< arc centre [mm]; its normal-axis coordinate equals start's
  bool clockwise = false;      ///< arcs: G2 (true) or G3 (false)
  Plane plane = Plane::xy;     ///< arcs: G17/G18/G19
  int turns = 1;               ///< arcs: number of times the arc passes the end angle (P word; 1 = usual)
  double feed = 0.0;           ///< programmed feed [mm/s]; for rapids the last programmed feed (not used)
  double spindle_rpm = 0.0;    ///< spindle speed [rev/min]; positive M3 (clockwise), negative M4, 0 off
  int tool = 0;                ///< tool number in the spindle (T … M6)
  long line = 0;               ///< 1-based source line the block came from (0 = not from a file)

  /// Throws std::invalid_argument naming the field if the block is degenerate or not finite.
  void validate() const;

  /// Path length [mm] (helical arcs: true 3-D length).
  double length() const noexcept;
  /// Signed sweep angle of an arc about the plane normal [rad]: negative for clockwise. 0 for lines.
  double sweep() const noexcept;
  /// Arc radius at the start [mm] (0 for lines).
  double radius() const noexcept;
  /// Point at fraction s ∈ [0, 1] of the block (arcs: by angle; radius and normal coordinate vary
  /// linearly so that s = 1 gives `end` exactly).
  Vec3 point_at(double s) const noexcept;
  /// Unit tangent (direction of travel) at fraction s ∈ [0, 1].
  Vec3 tangent_at(double s) const noexcept;
  /// Curvature [1/mm] at fraction s (0 for lines).
  double curvature() const noexcept;
};

}  // namespace netshape::toolpath
