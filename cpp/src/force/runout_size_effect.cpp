#include "netshape/force/runout_size_effect.hpp"

#include <array>
#include <cmath>
#include <vector>

#include "netshape/core/error.hpp"

namespace netshape::force {

namespace {
constexpr double two_pi = 2.0 * pi;
// knots of the piecewise-linear chip function, as fractions of the feed per tooth
constexpr std::array<double, 11> knot_fraction{0.0, 0.006, 0.02, 0.05, 0.1, 0.18, 0.3, 0.45, 0.62, 0.8, 1.0};

// base window ∩ {sin φ ≥ s} for a window inside [0, π]; false when empty
bool narrowed(const AngularEngagement& base, double s, AngularEngagement& out) {
  if (s >= 1.0) return false;
  double st = base.phi_st, ex = base.phi_ex;
  if (s > 0.0) {
    const double a = std::asin(s);
    st = std::max(st, a);
    ex = std::min(ex, pi - a);
  }
  if (!(ex > st)) return false;
  out.phi_st = st;
  out.phi_ex = ex;
  return true;
}

// g(h) = Σ_k w_k·max(0, h − h_k): the knots h_k and slope changes w_k of the piecewise-linear
// interpolant of h_ref·(h/h_ref)^p (p = 1: the single term h)
void chip_function(const RunoutSizeEffect& ext, double c, std::vector<double>& knots,
                   std::vector<double>& weights) {
  knots.assign(1, 0.0);
  weights.assign(1, 1.0);
  if (ext.chip_exponent == 1.0) return;
  const double href = ext.reference_chip > 0.0 ? ext.reference_chip : c;
  const double p = ext.chip_exponent;
  knots.clear();
  weights.clear();
  double prev_slope = 0.0;
  for (std::size_t i = 0; i + 1 < knot_fraction.size(); ++i) {
    const double h0 = c * knot_fraction[i], h1 = c * knot_fraction[i + 1];
    const double slope = href * (std::pow(h1 / href, p) - std::pow(h0 / href, p)) / (h1 - h0);
    knots.push_back(h0);
    weights.push_back(slope - prev_slope);
    prev_slope = slope;
  }
}

// r_j − r_{j+1} for every flute j (zeros without runout): with φ_j = θ + j·2π/N and φ growing with time,
// flute j + 1 passes every angle 2π/N before flute j, so flute j cuts the surface flute j + 1 left
std::vector<double> runout_steps(const RunoutSizeEffect& ext, int flutes) {
  std::vector<double> r(flutes), d(flutes);
  for (int j = 0; j < flutes; ++j) r[j] = ext.runout_rho * std::cos(ext.runout_lambda - two_pi * j / flutes);
  for (int j = 0; j < flutes; ++j) d[j] = r[j] - r[(j + 1) % flutes];
  return d;
}
}  // namespace

void RunoutSizeEffect::validate() const {
  NETSHAPE_CHECK_FINITE("runout_rho", runout_rho);
  NETSHAPE_CHECK(runout_rho >= 0.0, "runout_rho", runout_rho, "must be ≥ 0 [mm]");
  NETSHAPE_CHECK_FINITE("runout_lambda", runout_lambda);
  NETSHAPE_CHECK_FINITE("chip_exponent", chip_exponent);
  NETSHAPE_CHECK(chip_exponent > 0.0 && chip_exponent <= 2.0, "chip_exponent", chip_exponent, "must be in (0, 2]");
  NETSHAPE_CHECK_FINITE("reference_chip", reference_chip);
  NETSHAPE_CHECK(reference_chip >= 0.0, "reference_chip", reference_chip, "must be ≥ 0 [mm] (0: the feed per tooth)");
}

Points3 flat_end_forces_extended(const FlatEndModel& model, const RunoutSizeEffect& ext,
                                 const Eigen::Ref<const VectorXd>& angles) {
  model.validate();
  ext.validate();
  NETSHAPE_CHECK(model.engagement.phi_st >= 0.0 && model.engagement.phi_ex <= pi + 1e-12, "engagement",
                 model.engagement.phi_ex, "runout and size effect need a window inside [0, π] [rad]");
  if (ext.none()) return flat_end_forces(model, angles);
  const LinearEdgeCoefficients k = model.coefficient_model == FlatCoefficientModel::linear_edge
                                       ? model.linear_edge
                                       : model.kline_devor.to_linear_edge();
  const int N = model.flutes;
  const double c = model.feed_per_tooth;
  NETSHAPE_CHECK(c > 0.0, "feed_per_tooth", c, "must be positive with runout or a size effect [mm]");
  std::vector<double> knots, weights;
  chip_function(ext, c, knots, weights);
  const bool runout = ext.runout_rho != 0.0;
  FlatEndModel one = model;
  one.coefficient_model = FlatCoefficientModel::linear_edge;
  if (runout) one.flutes = 1;
  FlatEndWorkspace ws(one);
  const Eigen::Index n = angles.size();
  Points3 total = Points3::Zero(n, 3), part(n, 3);
  VectorXd shifted(n);
  const std::vector<double> steps = runout_steps(ext, N);
  const int groups = runout ? N : 1;
  for (int j = 0; j < groups; ++j) {
    const double delta = runout ? steps[j] : 0.0;
    shifted = angles.array() + (runout ? two_pi * j / N : 0.0);
    auto add = [&](double s, const LinearEdgeCoefficients& kk, double weight) {
      if (!narrowed(model.engagement, s, one.engagement)) return;
      one.linear_edge = kk;
      flat_end_forces(one, ws, shifted, part);
      total += weight * part;
    };
    for (std::size_t q = 0; q < knots.size(); ++q) {
      const double d = knots[q] - delta;  // element force ∝ c·sin φ − d where positive
      add(d / c, {k.ktc, k.krc, k.kac, -d * k.ktc, -d * k.krc, -d * k.kac}, weights[q]);
    }
    add(-delta / c, {0.0, 0.0, 0.0, k.kte, k.kre, k.kae}, 1.0);  // edge forces wherever h_j > 0
  }
  return total;
}

void flat_end_forces_extended(const FlatEndModel& model, const RunoutSizeEffect& ext, FlatEndWorkspace& ws,
                              const Eigen::Ref<const VectorXd>& angles, Eigen::Ref<Points3> out,
                              const EngagementMap& map) {
  ext.validate();
  if (ext.none()) return flat_end_forces(model, ws, angles, out, &map);
  flat_end_forces(model, ws, angles, out, &map);  // validates model, map and out; rebuilds ws if needed
  const LinearEdgeCoefficients k = model.coefficient_model == FlatCoefficientModel::linear_edge
                                       ? model.linear_edge
                                       : model.kline_devor.to_linear_edge();
  const int N = model.flutes, bins = map.bins();
  const double c = model.feed_per_tooth, dz = ws.disk_height(), kb = model.k_beta();
  NETSHAPE_CHECK(c > 0.0, "feed_per_tooth", c, "must be positive with runout or a size effect [mm]");
  std::vector<double> knots, weights;
  chip_function(ext, c, knots, weights);
  const std::vector<double> steps = runout_steps(ext, N);
  const VectorXd& z = ws.heights();
  for (Eigen::Index a = 0; a < angles.size(); ++a) {
    double fx = 0.0, fy = 0.0, fz = 0.0;
    for (int i = 0; i < ws.disks(); ++i)
      for (int j = 0; j < N; ++j) {
        double ph = std::fmod(angles[a] + two_pi * j / N - kb * z[i], two_pi);
        if (ph < 0.0) ph += two_pi;
        const int b = std::min(bins - 1, static_cast<int>(ph * bins / two_pi));
        if (!map.mask(i, b)) continue;
        const double sp = std::sin(ph), cp = std::cos(ph);
        const double h = c * sp + steps[j];  // this flute's chip: the runout step added
        if (!(h > 0.0)) continue;
        double g = 0.0;
        for (std::size_t q = 0; q < knots.size() && h > knots[q]; ++q) g += weights[q] * (h - knots[q]);
        const double ft = (k.ktc * g + k.kte) * dz, fr = (k.krc * g + k.kre) * dz;
        fx += -ft * cp - fr * sp;
        fy += ft * sp - fr * cp;
        fz += (k.kac * g + k.kae) * dz;
      }
    out(a, 0) = fx;
    out(a, 1) = fy;
    out(a, 2) = fz;
  }
}

}  // namespace netshape::force
