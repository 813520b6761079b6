#pragma once
/// \file moves.hpp
/// The motion between consecutive CL points as the machine executes it: the joints (X, Y, Z, tilt, C) move
/// linearly, J(λ) = J_0 + λ (J_1 − J_0), λ ∈ [0, 1], so the tool sweeps a curve in the workpiece frame.
///
/// Certified check: every point of the assembly moves at most S [mm] per unit λ,
///     table_ac: S = |ΔX| + (|ΔA| + |ΔC|)·(max(|X_0 − c|, |X_1 − c|) + reach)
///     head_bc:  S = |ΔX| + (|ΔB| + |ΔC|)·(pivot_length + reach)
/// (c the table centre, reach the largest distance of the solid from the tip; a rotation by an angle γ moves
/// a point at distance ρ from the rotation's centre by at most γρ). A sub-step [λ_0, λ_1] is free when the
/// posture at its middle keeps the clearance plus S·(λ_1 − λ_0)/2 (InterferenceChecker::clear_by); it
/// collides when that posture is closer than the clearance; otherwise it is halved, down to min_step (then
/// it counts as colliding). So "free" is certified for the whole continuous move.
///
/// Repair (repair_moves): a move between two final postures that collides gets a CL point in its middle —
/// CC point and normal the mean of its ends', axis half-way along the great circle, moved like a colliding
/// CC point's posture (repair_posture in the C-space of the middle point) when it collides or tilts beyond
/// θ_max — and both halves are checked again, to `max_depth` levels.
///
/// Rotary subdivision: where the tip of a joint-linear move leaves the straight chord between its CL points
/// by more than `chord` [mm] (sampled at 16 sub-steps), CL points are inserted on the chord (tip linear, axis
/// along the great circle) until it does not.

#include <vector>

#include "netshape/posture/assembly.hpp"
#include "netshape/posture/kinematics.hpp"
#include "netshape/posture/planner.hpp"

namespace netshape::posture {

/// Outcome of the check of one move.
struct MoveCheck {
  bool collides = false;  ///< some pose of the move is closer than the clearance (or undecided at min_step)
  double at = 0.0;        ///< λ of the colliding pose found (0 when free)
  int checks = 0;         ///< interference queries spent
};

/// The bound S [mm per unit λ] above for the move j0 → j1 (rows of 5: X, Y, Z [mm], tilt, C [rad]).
double move_speed_bound(const Kinematics& kin, const CutterAssembly& assembly, const Eigen::Ref<const VectorXd>& j0,
                        const Eigen::Ref<const VectorXd>& j1);
/// Certified check of the joint-linear move j0 → j1; min_step: smallest sub-step in λ.
MoveCheck check_move(const InterferenceChecker& checker, const Kinematics& kin, const Eigen::Ref<const VectorXd>& j0,
                     const Eigen::Ref<const VectorXd>& j1, double min_step = 1e-4);
/// check_move for every consecutive pair of joints (n, 5) → (n − 1).
std::vector<MoveCheck> check_moves(const InterferenceChecker& checker, const Kinematics& kin,
                                   const Eigen::Ref<const MatrixXdR>& joints, double min_step = 1e-4);

/// A planned path's CL points with the moves between them checked and repaired.
struct MovePlan {
  Points3 tips, axes;               ///< (m, 3) CL points: the final postures plus the inserted ones [mm]
  VectorXd source;                  ///< (m) CC index + fraction along the chord to the next CC point
  MatrixXdR joints;                 ///< (m, 5) X, Y, Z [mm], tilt, C [rad] of the points (plan_program)
  std::vector<bool> move_collides;  ///< (m − 1) the move from point k to k + 1 collides (certified check)
  int colliding_before = 0;         ///< moves between the final postures that collided before the repair
  int inserted = 0;                 ///< CL points inserted
  long checks = 0;                  ///< interference queries spent
};

/// Check every move between the final postures of `plan` on the machine `kin` and repair the colliding ones
/// (see above). options: the planner's (C-space sampling and tolerance of the inserted points).
MovePlan repair_moves(const InterferenceChecker& checker, const Kinematics& kin, const PlanResult& plan,
                      const PlanOptions& options = {}, int max_depth = 4);

/// The CL program of a planned path: repair_moves, then subdivide_rotary to `chord` [mm] > 0, then an
/// approach point `approach` [mm] ≥ 0 up the first axis before the first point and a retract point as far up
/// the last axis after the last (source −1 and n; none when approach = 0), the joints of every point, and the
/// certified check of every move of the result (move_collides).
MovePlan plan_program(const InterferenceChecker& checker, const Kinematics& kin, const PlanResult& plan,
                      const PlanOptions& options = {}, double approach = 10.0, double chord = 0.01,
                      int max_depth = 4);

/// CL points (tips (n, 3) [mm], unit axes (n, 3)) with points inserted on the chords wherever the machine's
/// tip would leave a chord by more than `chord` [mm] > 0. `source` (out, optional) gets, for every output
/// point, the input index it follows plus the fraction along that chord.
void subdivide_rotary(const Kinematics& kin, const Eigen::Ref<const Points3>& tips,
                      const Eigen::Ref<const Points3>& axes, double chord, Points3& out_tips, Points3& out_axes,
                      VectorXd* source = nullptr);

}  // namespace netshape::posture
