#pragma once
/// \file mb_spline.hpp
/// MB-spline (modified B-spline) of Park, Jung, Hwang, Jung, "A theoretical consideration for continuity
/// control of cutter posture", Proc. KSPE Conference, eq. (1) (matrix read as a quadratic in u): span i of control
/// points P_i … P_{i+3} is
///
///     r_i(u) = [1 u u²] · ¼ [[ 1, 2, 1, 0],
///                            [−2, 0, 2, 0],
///                            [ 1,−1,−1, 1]] · [P_i P_{i+1} P_{i+2} P_{i+3}]ᵀ,   0 ≤ u ≤ 1
///
/// so r_i(0) = (P_i + 2P_{i+1} + P_{i+2})/4, r_i(1) = r_{i+1}(0) (the joins) and
/// r_i'(0) = (P_{i+2} − P_i)/2 = r_{i−1}'(1) (C¹). The curve passes between the control points, which is
/// how it smooths the cutter posture vector end points (CPVE).

#include "netshape/core/types.hpp"

namespace netshape::posture {

/// Point of span `span` (0 ≤ span ≤ n − 4) at u ∈ [0, 1] of control points (n, 3), n ≥ 4.
Vec3 mb_spline_point(const Eigen::Ref<const Points3>& control, int span, double u);
/// First derivative dr/du there [mm].
Vec3 mb_spline_derivative(const Eigen::Ref<const Points3>& control, int span, double u);
/// The joins (P_i + 2P_{i+1} + P_{i+2})/4 for i = 0 … n − 3: (n − 2, 3).
Points3 mb_spline_joins(const Eigen::Ref<const Points3>& control);
/// Smoothed points (n, 3): each point replaced by the MB-spline join centred on it,
/// Q_i = (P_{i−1} + 2P_i + P_{i+1})/4, with the ends extended by reflection (P_{−1} = 2P_0 − P_1), which
/// keeps the end points; repeated `passes` ≥ 0 times.
Points3 mb_smooth(const Eigen::Ref<const Points3>& points, int passes = 1);

}  // namespace netshape::posture
