#pragma once
/// \file compiled_machine.hpp
/// A `Machine` compiled for evaluation: every constant the synthesis derives from the machine
/// (error functions prepared for fast evaluation, the six components of each axis packed for one
/// pass, the chains in evaluation order, axis directions with squareness, the tilted tool tip),
/// computed once and immutable afterwards. It is the *model* half of the pinocchio-style split; the
/// per-call scratch and outputs live in `MachineData` (synthesis.hpp). A CompiledMachine refers to its
/// machine's coefficient and table vectors: keep the machine alive and unchanged while it is in use.

#include <array>
#include <cstdint>
#include <vector>

#include "netshape/core/types.hpp"
#include "netshape/machine/machine.hpp"
#include "netshape/machine/table_interpolation.hpp"

namespace netshape::machine {

namespace detail {
/// One error function prepared for evaluation (points into the machine's vectors; evaluated by
/// `prepared_value` in cpp/src/machine/axis_components.hpp). A polynomial without coefficients is `zero`.
struct PreparedFunction {
  ErrorFunction::Kind kind = ErrorFunction::Kind::zero;
  OutOfRange out_of_range = OutOfRange::error;
  int n = 0;                              ///< coefficients or table points
  const double* c = nullptr;              ///< coefficients c0, c1, … or table values
  TableGrid grid;                         ///< table positions
  const ErrorFunction* source = nullptr;  ///< the function itself (its message for a refused position)
};

/// The six components of one axis prepared to be evaluated in one pass: all polynomials packed
/// (coefficient j of component c at [j * 6 + c], zero-padded to the highest degree: Horner gives the
/// same numbers as on the unpadded polynomial), or all tables on the same positions with the same
/// out-of-range policy (value i of component c at [i * 6 + c]: one lookup for six interpolations).
/// Other mixes (`generic`) are evaluated function by function.
struct AxisKernel {
  enum class Mode : std::uint8_t { generic = 0, polynomial = 1, table = 2 };
  Mode mode = Mode::generic;
  int terms = 0;                          ///< polynomial: coefficients per component; table: points
  std::vector<double> packed;             ///< packed coefficients or table values (see above)
  TableGrid grid;                         ///< table positions (in the machine's ErrorFunction)
  OutOfRange out_of_range = OutOfRange::error;
  const ErrorFunction* source = nullptr;  ///< a table of this axis, for the out-of-range message
};

/// One carriage of a chain in evaluation order (tool side from the spindle down to the bed, then the
/// workpiece side from the bed up to the table).
struct ChainStep {
  int axis = 0;
  bool tool = true;
  Vec3 origin = Vec3::Zero();  ///< Axis::origin [mm]
};
}  // namespace detail

/// The constants of a `Machine`, derived once (validates the machine). Immutable: one instance can
/// serve any number of `MachineData` workspaces, also on several threads.
struct CompiledMachine {
  explicit CompiledMachine(const Machine& machine);

  std::array<detail::PreparedFunction, 18> functions;  ///< [axis * 6 + component]
  std::array<detail::AxisKernel, 3> kernels;           ///< per axis: six components in one pass
  /// Per axis: periodic terms of its positioning component (an axis with terms is evaluated `generic`),
  /// as (amplitude [mm], 2π/period [1/mm], phase [rad]).
  std::array<std::vector<std::array<double, 3>>, 3> cyclic;
  std::array<detail::ChainStep, 3> steps;              ///< the chains in evaluation order
  int tool_steps = 0;                                  ///< steps[0, tool_steps) are tool side
  std::array<std::array<bool, 3>, 3> arm_grows{};      ///< [k][j]: axis j's Abbe arm grows with q_k

  std::array<Vec3, 3> direction;          ///< u'_k − u_k: deviation of the axis direction by squareness (exact)
  std::array<Vec3, 3> direction_linear;   ///< the same deviation to first order
  Vec3 tip_local;                         ///< deviation of the tilted tip from the nominal tip in the last
                                          ///< tool-side frame (exact) [mm]
  Vec3 tip_local_linear;                  ///< the same deviation to first order [mm]
  Vec3 tip_nominal;                       ///< tip without tilt in the last tool-side frame [mm]
};

}  // namespace netshape::machine
