#pragma once
/// \file calibration.hpp
/// Least-squares identification of cutting coefficients:
///  - closed-form mean forces of the linear edge model and the Altintas mean-force regression;
///  - the Kim et al. §4.2 (Table 1) procedure: ball-end K_T(ψ), K_R(ψ) cubics and exponents m_T, m_R
///    from mean slot forces over axial depths and feeds;
///  - fitting the linear edge coefficients and the angle offset to a measured force time series.

#include <vector>

#include "netshape/core/types.hpp"
#include "netshape/force/ball_end_model.hpp"
#include "netshape/force/coefficients.hpp"
#include "netshape/force/engagement.hpp"
#include "netshape/force/flat_end_model.hpp"

namespace netshape::force {

using Matrix36 = Eigen::Matrix<double, 3, 6>;

/// Mean force per revolution of the linear edge model is linear in the coefficients:
/// F̄ = M·(ktc, krc, kac, kte, kre, kae). M [mm² or mm] (3, 6), exact (helix-independent) for
/// a window inside one revolution:
///   F̄ = N·a/(2π) ∫_{φst}^{φex} (−dFt cos φ − dFr sin φ, dFt sin φ − dFr cos φ, dFa)/dz dφ.
/// Slot (0 … π): F̄x = −N a krc c/4 − N a kre/π, F̄y = N a ktc c/4 + N a kte/π,
/// F̄z = N a kac c/π + N a kae/2.
Matrix36 mean_force_matrix(const AngularEngagement& engagement, double feed_per_tooth, int flutes,
                           double axial_depth);
/// M·k [N].
Vec3 mean_force(const LinearEdgeCoefficients& k, const AngularEngagement& engagement,
                double feed_per_tooth, int flutes, double axial_depth);

struct LinearEdgeFit {
  LinearEdgeCoefficients coefficients;
  Vec3 r2 = Vec3::Zero();   ///< coefficient of determination per axis (x, y, z)
  Points3 residuals;        ///< measured − fitted mean forces, (n, 3) [N]
};

/// Altintas mean-force regression: mean forces (n, 3) [N] measured at feeds per tooth (n) [mm],
/// all with the same engagement, flutes and axial depth [mm]. Least squares of the stacked
/// F̄_i = M(c_i)·k (for a slot this is the classic three straight-line fits). n ≥ 2 distinct feeds.
LinearEdgeFit fit_linear_edge_mean_forces(const AngularEngagement& engagement, int flutes,
                                          double axial_depth, const Eigen::Ref<const VectorXd>& feeds,
                                          const Eigen::Ref<const Points3>& mean_forces);

/// Mean slot forces (F̄x, F̄y) [N] of a ball-end model per revolution for ξ = 0 and the slot
/// window, computed per element from ∫₀^π sin^{m+1} φ dφ (exact for the discretised model).
Vec3 ball_end_mean_slot_force(const BallEndModel& model);

struct BallEndFit {
  BallEndCoefficients coefficients;
  double rms_x = 0.0;  ///< rms residual of F̄x [N]
  double rms_y = 0.0;  ///< rms residual of F̄y [N]
};

/// Kim et al. §4.2: fit a0…a3, b0…b3, m_T, m_R to mean slot forces. Each test i has axial depth depths[i]
/// [mm], feed per tooth feeds[i] [mm] and measured mean (F̄x, F̄y) [N] in the cutting frame
/// (docs/conventions.md §2; F̄y carries the tangential coefficients, F̄x the radial ones). `geometry` gives
/// R, N, β and the discretisation (its coefficients, depth and feed are ignored). Separable least squares:
/// for each exponent the cubic is linear; the exponent is found by a grid scan in [m_min, m_max] and a
/// golden-section refinement. Needs ≥ 5 tests with ≥ 4 distinct depths and ≥ 2 distinct feeds.
BallEndFit fit_ball_end_mean_forces(const BallEndModel& geometry, const Eigen::Ref<const VectorXd>& depths,
                                    const Eigen::Ref<const VectorXd>& feeds,
                                    const Eigen::Ref<const VectorXd>& mean_fx,
                                    const Eigen::Ref<const VectorXd>& mean_fy, double m_min = 0.05,
                                    double m_max = 1.5);

/// Unit responses of the linear edge model: out[m] (n, 3) [N per unit coefficient] is the force
/// with coefficient m = 1 and the others 0 (m in ktc, krc, kac, kte, kre, kae order).
std::vector<Points3> linear_edge_basis(const FlatEndModel& model, const Eigen::Ref<const VectorXd>& angles);

struct TimeSeriesFit {
  LinearEdgeCoefficients coefficients;
  double phase = 0.0;        ///< angle offset [rad]: the model is evaluated at angles + phase
  Vec3 rms = Vec3::Zero();   ///< rms residual per axis [N]
  double rms_total = 0.0;    ///< rms over all three axes [N]
};

/// Least squares over a time series: the measured forces (n, 3) [N] at nominal rotation angles
/// (n) [rad] (e.g. 2π·rpm/60·t) are fitted by F(angles + phase) = Σ k_m B_m(angles + phase); the
/// coefficients are linear, the phase is scanned over one tooth period [0, 2π/N) in `phase_steps`
/// steps and refined by golden section. `model` gives geometry, feed and engagement.
TimeSeriesFit fit_linear_edge_time_series(const FlatEndModel& model, const Eigen::Ref<const VectorXd>& angles,
                                          const Eigen::Ref<const Points3>& forces, int phase_steps = 90);

}  // namespace netshape::force
