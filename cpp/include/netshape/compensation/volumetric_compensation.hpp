#pragma once
/// \file volumetric_compensation.hpp
/// Volumetric compensation of CL points (Yang & Kweon §4.2): commanded points P_cmd such that the
/// actual tool tip P_cmd + e(P_cmd) lands on the nominal point P_nom, with e from the exact error
/// synthesis of a machine::Machine.
///
/// Iteration: P ← P − (I + J₁)⁻¹·(P + e(P) − P_nom), J₁ the first-order Jacobian (chord Newton on the
/// exact residual; with J₁ = 0 this is the fixed point P ← P − (P + e(P) − P_nom) of Yang & Kweon, same
/// solution). Start: P_nom, or P_nom plus the previous point's correction when the previous point is
/// within 10 mm. (I + J₁)⁻¹ is computed at the start of a point and reused by the following points while
/// they stay within 10 mm of where it was computed (along a path: no Jacobian, 2 exact evaluations per
/// point). When a step does not at least halve the residual, the matrix is recomputed at the current
/// iterate, and if that does not help either the solver switches to Newton steps with a
/// finite-difference Jacobian. Every returned point's last evaluation is the exact residual.
/// Points that do not reach the tolerance within `max_iterations` are reported (status) or thrown
/// (netshape::Error) — never returned silently.

#include <cstdint>
#include <vector>

#include "netshape/core/error.hpp"
#include "netshape/core/types.hpp"
#include "netshape/machine/machine.hpp"
#include "netshape/machine/synthesis.hpp"

namespace netshape::compensation {

/// Options of the volumetric compensation.
struct VolumetricOptions {
  double tolerance = 1e-9;    ///< residual |P_cmd + e(P_cmd) − P_nom| to reach [mm], > 0
  int max_iterations = 50;    ///< evaluations per point, ≥ 1
  bool check_travel = true;   ///< refuse commanded points outside the axis travel
  void validate() const;
};

/// Outcome for one point.
enum class VolumetricStatus : std::uint8_t {
  ok = 0,
  not_converged = 1,   ///< residual above tolerance after max_iterations
  outside_travel = 2,  ///< the commanded point leaves the travel of `axis`
  outside_table = 3,   ///< an error table with out_of_range = error was left during the iteration
};

/// Result of compensating n points.
struct VolumetricResult {
  Points3 commanded;                    ///< (n, 3) compensated commanded points [mm]
  Eigen::VectorXd residual;             ///< (n,) final |P_cmd + e(P_cmd) − P_nom| [mm]
  Eigen::VectorXi iterations;           ///< (n,) error evaluations used
  std::vector<VolumetricStatus> status; ///< (n,) per point
  Eigen::VectorXi axis;                 ///< (n,) offending axis for outside_travel (0..2), else −1
  bool all_ok() const;
  /// Index of the first point whose status is not ok, or −1.
  long first_failure() const;
};

/// Compensate one point (no allocation). Returns the status; writes the commanded point, residual
/// and evaluation count; `axis` gets the offending axis when outside travel.
VolumetricStatus compensate_point(const machine::Machine& machine, machine::MachineData& data,
                                  const Vec3& nominal, const VolumetricOptions& options, Vec3& commanded,
                                  double& residual, int& iterations, int& axis);

/// Compensate (n, 3) nominal points [mm]. Never throws for per-point failures (see status).
/// Runs the iteration above for `machine::batch_lanes` points at once: lane l takes the contiguous run
/// [l·n/lanes, (l+1)·n/lanes) in order (its own warm start and step matrix, as one by one) and one vectorised
/// `machine::tip_error_lanes` call evaluates all lanes. Here the step matrix is (I + J)⁻¹ of the exact
/// Jacobian, and the first step after computing it also subtracts (I + J)⁻¹·½H[d, d] (second derivative of
/// the first-order model along the linear step d, from the same evaluation): a cold point costs 2 exact
/// evaluations (residual after one step ~1e-12 mm on the Yang & Kweon HMC). A point that leaves the chord iteration (slow
/// contraction right after a fresh step matrix, max_iterations, a table left, not finite) is solved again
/// by `compensate_point` from a cold start: its result and status are that function's. The commanded points
/// equal the one-by-one ones to the tolerance (only the starts differ).
VolumetricResult compensate_points_status(const machine::Machine& machine,
                                          const Eigen::Ref<const Points3>& nominal,
                                          const VolumetricOptions& options = {});

/// Compensate (n, 3) nominal points [mm] and return the (n, 3) commanded points. Throws
/// std::invalid_argument naming the point index and axis for a point outside travel or a table,
/// netshape::Error for a point that did not converge.
Points3 compensate_points(const machine::Machine& machine, const Eigen::Ref<const Points3>& nominal,
                          const VolumetricOptions& options = {});

}  // namespace netshape::compensation
