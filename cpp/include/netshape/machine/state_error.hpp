#pragma once
/// \file state_error.hpp
/// Errors of the tool tip that depend on the machine's state rather than on its position alone:
/// backlash (the direction each axis last moved in) and thermal drift (the program time).
///
///   s(d, t) = Σ_k ½·backlash_k·d_k·ê_k + Σ_j amplitude_j·(1 − exp(−t/τ_j))·ê_axis(j)
///
/// d_k ∈ {−1, +1} is the direction axis k last moved in (its approach direction), t the program
/// time [s]. The tip commanded to p with state (d, t) lands at p + e(p) + s(d, t), e the geometric
/// error of synthesis.hpp. Compensation solves P + e(P) = P_nom − s(d, t) (s does not depend on P).

#include "netshape/core/types.hpp"
#include "netshape/machine/machine.hpp"

namespace netshape::machine {

/// s(d, t) [mm] for directions `direction` (3,) (each −1, 0 or +1; 0: no backlash term) and time t [s].
Vec3 state_error(const Machine& machine, const Vec3& direction, double time) noexcept;

/// s(d, t) for many points: directions (n, 3), times (n,) [s] → (n, 3) [mm]. Throws
/// std::invalid_argument on a size mismatch or a non-finite value.
Points3 state_error(const Machine& machine, const Eigen::Ref<const Points3>& directions,
                    const Eigen::Ref<const Eigen::VectorXd>& times);

/// Approach directions along a path of points (n, 3) [mm]: row i holds, per axis, the sign of the
/// last change of that axis' coordinate up to point i (changes below `resolution` [mm] ignored), or
/// `initial` (3,) before the axis first moves.
Points3 approach_directions(const Eigen::Ref<const Points3>& path, const Vec3& initial = Vec3(1, 1, 1),
                            double resolution = 1e-9);

}  // namespace netshape::machine
