#pragma once
/// \file machine.hpp
/// A 3-axis machine tool with linear axes X, Y, Z as two kinematic chains from the bed: the tool
/// side (bed → … → spindle → tool tip) and the workpiece side (bed → … → table → workpiece), each
/// axis carrying its six ISO 230-1 error components as functions of its own position, three
/// squareness errors and the spindle tilt. This is the user's plain description; the constants the
/// synthesis derives from it live in `CompiledMachine` (compiled_machine.hpp), evaluation scratch in
/// `MachineData` (synthesis.hpp).
///
/// ISO 230-1 names (axis k ∈ {X, Y, Z}): EXk, EYk, EZk translation error motions along X, Y, Z
/// [mm] (EKk: positioning, the two others: straightness); EAk, EBk, ECk rotation error motions
/// about X, Y, Z [rad] (roll, pitch, yaw depending on k). Squareness: EC0Y (Y about Z, reference
/// axis X), EB0Z (Z about Y, reference axis X), EA0Z (Z about X, reference axis Y) [rad].
///
/// Yang & Kweon's symbols (docs/references.md), one to one (first subscript = direction, second = axis):
///   δ_xx δ_yx δ_zx δ_xy δ_yy δ_zy δ_xz δ_yz δ_zz  →  EXX EYX EZX EXY EYY EZY EXZ EYZ EZZ
///   ε_xx ε_yx ε_zx ε_xy ε_yy ε_zy ε_xz ε_yz ε_zz  →  EAX EBX ECX EAY EBY ECY EAZ EBZ ECZ
///   S_xy → EC0Y, S_yz (= S_zy in eq. 7) → EA0Z, S_zx → −EB0Z, ε_xs → spindle_tilt_a, ε_ys → spindle_tilt_b,
///   L → tool_length, (T_x, T_y, T_z) → spindle_nose, Oxy / Ozx → Axis::origin.
/// Signs: the paper writes the motion of each carriage; netshape writes every component in the
/// sense of ISO 230-1 measurements — the motion of the tool relative to the workpiece caused by
/// that axis. On the tool side the two agree; for a workpiece-side axis (the paper's Z table) the
/// paper's δ_iz = −E{I}Z exactly and ε_iz = −E{A,B,C}Z to first order (the paper's table turns by
/// R(ε), netshape's by R(E)ᵀ), with the table position z_table = −q_Z. See docs/machine.md.

#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "netshape/core/types.hpp"
#include "netshape/machine/error_function.hpp"

namespace netshape::machine {

/// Index of an error component within an axis: translations along X, Y, Z, rotations about X, Y, Z.
enum class Component : std::uint8_t { ex = 0, ey = 1, ez = 2, ea = 3, eb = 4, ec = 5 };

/// Which chain an axis belongs to.
enum class Side : std::uint8_t { tool = 0, workpiece = 1 };

/// ISO 230-1 name of component `c` of axis `axis` (0 = X, 1 = Y, 2 = Z), e.g. (ea, 0) → "EAX".
std::string component_name(Component c, int axis);

/// A periodic positioning error of an axis (ball-screw pitch error, encoder interpolation error):
/// added to the axis' positioning component EKk as amplitude·sin(2π·q/period + phase), q the axis
/// position [mm].
struct CyclicTerm {
  double amplitude = 0.0;  ///< [mm], ≥ 0
  double period = 1.0;     ///< [mm], > 0
  double phase = 0.0;      ///< [rad]
};

/// Thermal drift of the tool tip relative to the workpiece along one axis as a function of the
/// program time t [s]: amplitude·(1 − exp(−t/time_constant)) (a first-order warm-up from t = 0).
struct ThermalDrift {
  int axis = 0;                ///< 0 = X, 1 = Y, 2 = Z
  double amplitude = 0.0;      ///< [mm]
  double time_constant = 1.0;  ///< τ [s], > 0
};

/// One linear axis. Its position q [mm] is the program coordinate along its direction (ISO 841:
/// the motion of the tool relative to the workpiece), whichever chain carries it.
struct Axis {
  double travel_min = -1e9;                ///< lowest allowed position [mm]
  double travel_max = 1e9;                 ///< highest allowed position [mm]
  Vec3 origin = Vec3::Zero();              ///< offset of this carriage's frame from the previous frame in the
                                           ///< chain (bed or the axis below) [mm]; the paper's Oxy, Ozx
  std::array<ErrorFunction, 6> errors{};   ///< indexed by Component: EXk, EYk, EZk [mm]; EAk, EBk, ECk [rad]
  std::vector<CyclicTerm> cyclic;          ///< periodic terms added to the positioning component EKk
  double backlash = 0.0;                   ///< reversal value [mm]: the tip lands backlash/2 further along
                                           ///< the axis' last direction of motion (state_error.hpp)

  const ErrorFunction& error(Component c) const { return errors[static_cast<int>(c)]; }
  ErrorFunction& error(Component c) { return errors[static_cast<int>(c)]; }
};

/// The machine model. Plain value type; `validate()` checks it.
struct Machine {
  std::string name;
  std::array<Axis, 3> axes{};        ///< X, Y, Z
  std::vector<int> tool_chain;       ///< axis indices (0 = X, 1 = Y, 2 = Z) from the bed outward to the spindle
  std::vector<int> workpiece_chain;  ///< axis indices from the bed outward to the workpiece
  double ec0y = 0.0;                 ///< squareness of Y about Z, reference X [rad]
  double eb0z = 0.0;                 ///< squareness of Z about Y, reference X [rad]
  double ea0z = 0.0;                 ///< squareness of Z about X, reference Y [rad]
  double spindle_tilt_a = 0.0;       ///< tilt of the spindle axis about X [rad] (Yang & Kweon ε_xs)
  double spindle_tilt_b = 0.0;       ///< tilt of the spindle axis about Y [rad] (Yang & Kweon ε_ys)
  Vec3 spindle_nose = Vec3::Zero();  ///< gauge point of the spindle in the last tool-side frame [mm] (T)
  double tool_length = 0.0;          ///< tool length from the gauge point to the tip [mm] (L), ≥ 0
  Vec3 tool_direction = Vec3(0, 0, -1);  ///< unit vector from gauge point to tip, last tool-side frame
  std::vector<ThermalDrift> thermal;     ///< drift of the tip with program time (state_error.hpp)

  /// Throws std::invalid_argument naming the field: every axis exactly once in the two chains,
  /// travel_min < travel_max, finite numbers, unit tool direction, valid error functions, cyclic
  /// periods and thermal time constants > 0.
  void validate() const;

  /// True when some axis has a backlash or the machine a thermal drift: errors that depend on the
  /// direction of motion or the program time, not on the position alone (state_error.hpp).
  bool has_state_errors() const noexcept;

  /// Side of axis `axis` (0..2).
  Side side(int axis) const;

  /// Nominal tool tip in the last tool-side frame (no spindle tilt) [mm].
  Vec3 nominal_tip() const { return spindle_nose + tool_length * tool_direction; }
};

/// A machine with the given chains and no errors, unlimited travel (handy in tests and examples).
Machine ideal_machine(std::vector<int> tool_chain, std::vector<int> workpiece_chain,
                      double tool_length = 0.0);

}  // namespace netshape::machine
