#pragma once
/// \file planner.hpp
/// Posture planning along a path of CC points (Park, Jung, Hwang, Jung, KSPE): normal posture (raw) →
/// C-space and MC-space move of every posture (§2) → MB-spline smoothing of the posture-vector end points
/// (§3–4) → re-check and repair of smoothed postures that entered an obstacle.
///
/// Posture vector: start CPVS_i = ball centre O_i = CC_i + R·n_i (fixed for a ball end mill), end
/// CPVE_i = O_i + L·T_i with L = vector_length [mm]. Smoothing replaces CPVE by mb_smooth(CPVE, passes)
/// and rebuilds T'_i = unit(CPVE'_i − CPVS_i). A smoothed posture that collides is repaired: the segment
/// in the polar C-space plane from it to the nearest free grid posture of its C-space is bisected to the
/// angular tolerance and the free end taken (the smallest move found along that segment).
///
/// Smoothness: the posture change between neighbours is the angle between T_i and T_{i+1} divided by
/// the path length between the CC points [rad/mm].

#include <vector>

#include "netshape/posture/assembly.hpp"
#include "netshape/posture/cspace.hpp"

namespace netshape::posture {

struct PlanOptions {
  CSpaceOptions cspace;
  int passes = 3;              ///< MB-spline smoothing passes (≥ 0)
  double vector_length = 0.0;  ///< L of the posture vector [mm]; 0 = the assembly's holder_length
  void validate() const;
};

/// One stage of postures along the path.
struct PostureSet {
  Points3 tips;     ///< (n, 3) tool tip (lowest point of the ball along the axis) [mm]
  Points3 axes;     ///< (n, 3) unit axis from the tip towards the spindle
  Points2 angles;   ///< (n, 2) posture (θ, φ) in the CC point's frame [rad]
  std::vector<bool> collides;  ///< (n) interference (closer than the clearance)
  int collision_count() const;
};

struct PlanResult {
  VectorXd s;             ///< (n) path length of the CC points [mm]
  Points3 cc, normals, feeds;  ///< (n, 3) CC points [mm], unit normals, unit feed directions (⟂ n)
  PostureSet raw, mc, smoothed, final_;  ///< normal posture, MC-space, MB-smoothed, repaired
  std::vector<bool> repaired;  ///< (n) smoothed posture collided and was repaired
  std::vector<CSpace> cspaces; ///< (n) C-space of each CC point
  long checks = 0;             ///< interference checks spent in total
  int repaired_count() const;
};

/// Plan postures for CC points (n, 3) with unit normals (n, 3) (towards the tool), n ≥ 2; feed directions
/// are the central differences of the CC points. Throws std::invalid_argument naming the CC point index
/// for a degenerate normal, coincident neighbours, or a point no posture up to theta_max can reach.
PlanResult plan(const InterferenceChecker& checker, const Eigen::Ref<const Points3>& cc,
                const Eigen::Ref<const Points3>& normals, const PlanOptions& options = {});

/// Largest angle between neighbouring axes divided by the path length between them [rad/mm].
double max_posture_change(const Eigen::Ref<const VectorXd>& s, const Eigen::Ref<const Points3>& axes);

}  // namespace netshape::posture
