#pragma once
/// \file kinematics.hpp
/// Rotary-axis angles of two 5-axis machine types from tool tip + tool axis in the workpiece frame.
///
/// table_ac (table-tilting trunnion: A about machine X carries the C table about Z; the spindle is fixed
/// along machine +Z). A workpiece point p maps to machine coordinates
///     X = centre + R_x(A)·R_z(C)·p,   and the tool axis a must map to +Z: R_x(A)·R_z(C)·a = ẑ, so
///     a = (sin A·sin C, sin A·cos C, cos A).
/// head_bc (head-tilting: C about machine Z carries the B head about Y; the workpiece is fixed):
///     a = R_z(C)·R_y(B)·ẑ = (sin B·cos C, sin B·sin C, cos B),   X = tip + pivot_length·a.
/// Each axis has two solutions, (tilt, C) and (−tilt, C + π). Along a path the solution nearest the previous
/// one (|Δtilt| + |ΔC|, C unwrapped without limit) within the tilt limits is kept, so the branch stays
/// continuous; where the axis lies on the C axis (sin tilt = 0, the singularity) C keeps its previous value
/// instead of flipping. Angles in rad, lengths in mm.

#include <cstdint>

#include "netshape/core/types.hpp"

namespace netshape::posture {

enum class MachineKind : std::uint8_t { table_ac = 0, head_bc = 1 };

struct Kinematics {
  MachineKind kind = MachineKind::table_ac;
  Vec3 table_centre = Vec3::Zero();  ///< table_ac: machine position of the workpiece origin at A = C = 0 [mm]
  double pivot_length = 0.0;         ///< head_bc: tool tip to the head's pivot along the axis [mm], ≥ 0
  double tilt_min = -2.0943951023931953;  ///< lower limit of A (or B) [rad] (−120°)
  double tilt_max = 2.0943951023931953;   ///< upper limit of A (or B) [rad] (+120°)
  /// Throws std::invalid_argument naming the field.
  void validate() const;
};

/// Machine joints (n, 5): X, Y, Z [mm], tilt (A or B) [rad], C [rad] for tips (n, 3) [mm] and axes (n, 3)
/// (unit, from the tip into the spindle) in the workpiece frame. c_start: C to stay near at the first point
/// [rad]. Throws std::invalid_argument naming the point index when no solution lies within the tilt limits.
MatrixXdR inverse_kinematics(const Kinematics& kin, const Eigen::Ref<const Points3>& tips,
                             const Eigen::Ref<const Points3>& axes, double c_start = 0.0);
/// Tips (n, 3) and unit axes (n, 3) in the workpiece frame from joints (n, 5).
void forward_kinematics(const Kinematics& kin, const Eigen::Ref<const MatrixXdR>& joints, Points3& tips,
                        Points3& axes);

}  // namespace netshape::posture
