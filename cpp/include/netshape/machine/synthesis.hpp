#pragma once
/// \file synthesis.hpp
/// Error synthesis: the tool-tip position error relative to the workpiece, from the product of
/// homogeneous transforms along the two chains of a `Machine`.
///
/// Frames and conventions (docs/machine.md has the derivation):
///  - Program point p = (x, y, z) [mm]: nominal tool tip relative to the workpiece; axis k sits at
///    q_k = p_k.
///  - Axis k's error motion: rotation R_k = R(EAk, EBk, ECk) and translation t_k (below), with
///    R(a, b, c) = Rz(c)·Ry(b)·Rx(a) (exact, no small-angle approximation) and u'_k the axis
///    direction turned by the squareness errors (Y: Rz(EC0Y)·ŷ; Z: Rx(EA0Z)·Ry(EB0Z)·ẑ; X: x̂).
///  - Tool side: carriage k relative to the frame below = Trans(origin_k)·Trans(t_k)·R_k, with
///    t_k = q·u'_k + (EXk, EYk, EZk): the carriage moves by t_k and turns by R_k about its own origin.
///    Workpiece side: carriage k relative to the frame below = Trans(origin_k)·Trans(−t_k)·R_kᵀ: the
///    table moves by −t_k and turns by R_kᵀ about its own origin, so the components describe the
///    tool's motion relative to the workpiece (ISO 230-1 sense) and the Abbe arm is the point
///    relative to the table's current origin.
///  - Tool tip in the last tool-side frame: spindle_nose + L·Rx(tilt_a)·Ry(tilt_b)·tool_direction.
///  - Actual point W(p): the tool tip expressed in the workpiece frame; error e(p) = W(p) − W_nominal(p),
///    so the tip lands at p + e(p) in program coordinates. eq. (3) of Yang & Kweon, ΔW_B.
///  - First order: e₁(p) = Σ_k [δ_k + q_k·(u'_k − u_k)₁ + ε_k × r_k] + L·(θ_s × d), r_k the nominal arm
///    from carriage k's frame origin to the tip (tool side) or to the workpiece point (workpiece
///    side) — Yang & Kweon eq. (9)–(11) for any chain. exact − first order = O(error²).

#include <array>
#include <cstdint>
#include <memory>
#include <vector>

#include "netshape/core/types.hpp"
#include "netshape/machine/compiled_machine.hpp"
#include "netshape/machine/machine.hpp"

namespace netshape::machine {

/// Which synthesis to use.
enum class Order : std::uint8_t { exact = 0, first = 1 };

/// Points per call of `tip_error_lanes`.
constexpr int batch_lanes = 8;

/// Workspace for evaluating a `Machine` (the *data* half of the pinocchio-style Model/Data split): the
/// per-point scratch and the outputs the evaluation functions leave, next to a shared, immutable
/// `CompiledMachine` (the constants). Build one per thread; the evaluation functions never allocate.
/// Through its CompiledMachine a MachineData refers to its machine's error tables: keep the machine
/// alive and unchanged while the data is in use (build a new one after changing the machine).
struct MachineData {
  /// Compiles `machine` (validates it) for this workspace alone.
  explicit MachineData(const Machine& machine);
  /// A workspace on an already compiled machine (several workspaces, e.g. one per thread, share it).
  explicit MachineData(std::shared_ptr<const CompiledMachine> compiled);

  /// The constants this workspace evaluates.
  const CompiledMachine& compiled() const noexcept { return *compiled_; }

  // per-point scratch (filled by evaluate_components, first-order tip_error and tip_error_and_jacobian)
  std::array<Vec3, 3> delta;              ///< (EXk, EYk, EZk) at the current point [mm]
  std::array<Vec3, 3> epsilon;            ///< (EAk, EBk, ECk) at the current point [rad]
  std::array<Vec3, 3> delta_slope;        ///< d(EXk, EYk, EZk)/dq_k [mm/mm] (Jacobian only)
  std::array<Vec3, 3> epsilon_slope;      ///< d(EAk, EBk, ECk)/dq_k [rad/mm] (Jacobian only)
  /// Second-order terms of the first-order model, left by `tip_error_lanes` when it computes Jacobians,
  /// point i in [..][i]: [3k + c] = (δ''_k + ε''_k × r_k)_c [mm/mm²] for a polynomial axis k (0 for
  /// tables and axes evaluated per point), [9 + 3k + c] = ε'_k,c [rad/mm]. With them the second
  /// derivative of e₁ along d is Σ_k d_k² g_k + 2 Σ_k d_k ε'_k × (Σ_{m: r_k grows with q_m} d_m u_m)
  /// (compensation: second-order first step).
  double lane_curvature[18][batch_lanes];
  /// The exact Jacobian ∂e/∂p of each point (forward differentiation along the chain), left by
  /// `tip_error_lanes` when it computes Jacobians: [3 * col + row][i] (approximate for a point whose
  /// angles exceed 1e-3 rad).
  double lane_jacobian[9][batch_lanes];

 private:
  std::shared_ptr<const CompiledMachine> compiled_;
};

/// Evaluate the six components of each axis at program point p into `data.delta`/`data.epsilon`.
/// Throws std::invalid_argument when a table's out-of-range policy is `error` and p is outside.
void evaluate_components(const Machine& machine, MachineData& data, const Vec3& p);

/// Tip error e(p) [mm] relative to the workpiece at program point p [mm] (one point, no allocation).
Vec3 tip_error(const Machine& machine, MachineData& data, const Vec3& p, Order order = Order::exact);

/// Exact tip error e(p) [mm] and the Jacobian ∂e₁/∂p of the first-order model at p (3×3,
/// dimensionless; column k = derivative along program axis k). The compensation's Newton step uses it:
/// the Jacobian differs from the exact one by O(error²), which only slows convergence, never changes the
/// fixed point.
Vec3 tip_error_and_jacobian(const Machine& machine, MachineData& data, const Vec3& p, Mat3& jacobian);

/// Exact tip errors of `batch_lanes` points at once, vectorised over the points (structure of arrays;
/// AVX-512 or AVX2 when the CPU has them, else SSE2), the same synthesis as `tip_error(…, Order::exact)`
/// (the same operations in the same order per point and no fused multiply-add, so every instruction set
/// gives the one-point function's results bit for bit). p[c][i]: coordinate c of point i [mm]; e[c][i]: error
/// component c [mm]. With `jacobian` non-null, also the first-order Jacobian of each point as
/// `tip_error_and_jacobian` gives it: (*jacobian)[3 * col + row][i]. Never throws: returns a bit mask
/// of the points (bit i = point i) that left a table with out_of_range = error or are not finite
/// (their outputs are meaningless; the per-point functions throw for them).
unsigned tip_error_lanes(MachineData& data, const double (&p)[3][batch_lanes], double (&e)[3][batch_lanes],
                         double (*jacobian)[9][batch_lanes] = nullptr);

namespace detail {
/// Whether this build and CPU run `tip_error_lanes` with `width` points per vector (1, 2, 4 or 8).
bool lanes_width_supported(int width);
/// `tip_error_lanes` with a chosen vector width (tests: every variant gives the same numbers).
unsigned tip_error_lanes_width(int width, MachineData& data, const double (&p)[3][batch_lanes],
                               double (&e)[3][batch_lanes], double (*jacobian)[9][batch_lanes] = nullptr);
}  // namespace detail

/// Tip errors at many points: (n, 3) [mm] in, (n, 3) [mm] out.
Points3 tip_error(const Machine& machine, const Eigen::Ref<const Points3>& points,
                  Order order = Order::exact);

/// Where the tip actually lands for commanded points (p + e(p)): (n, 3) [mm].
Points3 actual_points(const Machine& machine, const Eigen::Ref<const Points3>& commanded,
                      Order order = Order::exact);

/// Volumetric error VE = |e(p)| (Yang & Kweon eq. 16) at many points: (n,) [mm].
Eigen::VectorXd volumetric_error(const Machine& machine, const Eigen::Ref<const Points3>& points,
                                 Order order = Order::exact);

/// Exact rotation R(a, b, c) = Rz(c)·Ry(b)·Rx(a) [rad], sin/cos exact to rounding (short Taylor
/// series below 0.05 rad, std::sin/cos above).
Mat3 rotation_zyx(double a, double b, double c) noexcept;

}  // namespace netshape::machine
