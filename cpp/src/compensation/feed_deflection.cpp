// The deflection and wall-error limits of a force sample (compensation/feed_deflection.hpp).
#include "compensation/feed_deflection.hpp"

#include <algorithm>
#include <cmath>

namespace netshape::compensation::detail {

namespace {
constexpr double inf = std::numeric_limits<double>::infinity();
constexpr double two_pi = 2.0 * pi;

/// Largest c ≥ 0 with max_k |c·a_k + b_k| ≤ limit (a, b per wall level) [mm/tooth].
double largest_linear(const VectorXd& a, const VectorXd& b, double limit) {
  double best = inf;
  for (Eigen::Index k = 0; k < a.size(); ++k) {
    if (std::abs(b[k]) > limit) return 0.0;
    if (a[k] > 0.0) best = std::min(best, (limit - b[k]) / a[k]);
    if (a[k] < 0.0) best = std::min(best, (-limit - b[k]) / a[k]);
  }
  return best;
}
}  // namespace

SampleDeflection::SampleDeflection(const cutter::Cutter& cutter, const force::LinearEdgeCoefficients& k,
                                   double disk_height, const VectorXd& angles)
    : cutter_(cutter), full_(k), cut_(k), edge_(k), angles_(angles) {
  cut_.kte = cut_.kre = cut_.kae = 0.0;
  edge_.ktc = edge_.krc = edge_.kac = 0.0;
  auto& fm = model_.force;
  fm.radius = cutter.radius;
  fm.flutes = cutter.flutes;
  fm.helix = cutter.helix;
  fm.coefficient_model = force::FlatCoefficientModel::linear_edge;
  fm.linear_edge = full_;
  fm.disk_height = disk_height;
  fm.feed_per_tooth = 1.0;
  fm.axial_depth = std::min(1.0, cutter.flute_length);
  model_.beam = deflection::Cantilever::tool(cutter.diameter(), cutter.stick_out, cutter.youngs_modulus,
                                             deflection::InertiaModel::square);
  model_.load = deflection::LoadModel::distributed;
  model_.smooth_edges = true;
  model_.holder_compliance = cutter.holder_compliance;
  model_.chip.runout_rho = cutter.runout_rho;
  model_.chip.runout_lambda = cutter.runout_lambda;
  model_.validate();
  P_.resize(angles.size(), 3);
  Q_.resize(angles.size(), 3);
}

double SampleDeflection::tip_peak(double c) {
  model_.force.feed_per_tooth = c;
  model_.force.linear_edge = full_;
  double m = 0.0;
  for (Eigen::Index a = 0; a < angles_.size(); ++a) {
    deflection::disk_forces(model_, ws_, angles_[a]);
    m = std::max(m, deflection::deflection_from_forces(model_, ws_, 0.0).norm());
  }
  return m;
}

double SampleDeflection::wall_peak(double c, int walls) {
  model_.force.feed_per_tooth = c;
  model_.force.linear_edge = full_;
  const VectorXd levels = deflection::cut_levels(model_.force.axial_depth);
  double m = 0.0;
  for (const auto side : {deflection::WallSide::left, deflection::WallSide::right}) {
    if (!(walls & (side == deflection::WallSide::left ? 1 : 2))) continue;
    m = std::max(m, deflection::wall_errors(model_, ws_, side, levels).error.cwiseAbs().maxCoeff());
  }
  return m;
}

/// P_, Q_: the tip deflection (δx, δy, 0) per angle of the cutting part at c = 1 and of the edge part.
void SampleDeflection::tip_parts() {
  model_.force.feed_per_tooth = 1.0;
  for (int part = 0; part < 2; ++part) {
    model_.force.linear_edge = part == 0 ? cut_ : edge_;
    Points3& out = part == 0 ? P_ : Q_;
    for (Eigen::Index a = 0; a < angles_.size(); ++a) {
      deflection::disk_forces(model_, ws_, angles_[a]);
      const Vec2 d = deflection::deflection_from_forces(model_, ws_, 0.0);
      out.row(a) << d.x(), d.y(), 0.0;
    }
  }
}

SampleDeflection::Result SampleDeflection::evaluate(const stock::ZMap& stock, const Vec3& tip,
                                                    const Vec3& direction, int walls, double c0,
                                                    double max_deflection, double max_wall_error) {
  Result r;
  const stock::Immersion im = stock::immersion(stock, cutter_, tip, direction);
  if (!im.engaged || im.axial_depth <= 1e-9) return r;
  auto& fm = model_.force;
  fm.axial_depth = std::min(im.axial_depth, cutter_.flute_length);
  double st = im.phi_st - two_pi * std::floor(im.phi_st / two_pi);
  double ex = st + std::min(im.phi_ex - im.phi_st, two_pi);
  // a generated wall is where the window ends (deflection/wall.hpp): the window reaches φ = 0 (left)
  // or π (right) exactly, whatever the Z-map's cells near the wall say (their half-cell steps and the
  // sliver between two samples' discs would move the edge by ~0.1 rad)
  if (walls & 1) st = ex - (ex - two_pi * std::floor(ex / two_pi));
  if (walls & 2) {
    const double to_pi = (pi - st) - two_pi * std::floor((pi - st) / two_pi);
    if (to_pi > 0.0) ex = st + to_pi;
  }
  if (!(ex > st) || ex - st > two_pi) ex = st + std::min(im.phi_ex - im.phi_st, two_pi);
  if (st >= two_pi) {
    st -= two_pi;
    ex -= two_pi;
  }
  fm.engagement.phi_st = st;
  fm.engagement.phi_ex = ex;
  ws_.ensure(model_);
  const bool wall_limit = std::isfinite(max_wall_error) && walls != 0;
  if (!model_.chip.none()) {
    if (std::isfinite(max_deflection)) {
      r.deflection_c = largest_below([&](double c) { return tip_peak(c); }, max_deflection);
      r.deflection = tip_peak(c0);
    }
    if (wall_limit) {
      r.wall_c = largest_below([&](double c) { return wall_peak(c, walls); }, max_wall_error);
      r.wall_error = wall_peak(c0, walls);
    }
    return r;
  }
  if (std::isfinite(max_deflection)) {
    tip_parts();
    r.deflection_c = detail::largest_feed_per_tooth(P_, Q_, 1.0, 0.0, Vec3(1, 1, 0), max_deflection);
    for (Eigen::Index a = 0; a < P_.rows(); ++a)
      r.deflection = std::max(r.deflection, (c0 * P_.row(a) + Q_.row(a)).norm());
  }
  if (wall_limit) {
    const VectorXd levels = deflection::cut_levels(fm.axial_depth);
    fm.feed_per_tooth = 1.0;
    for (const auto side : {deflection::WallSide::left, deflection::WallSide::right}) {
      if (!(walls & (side == deflection::WallSide::left ? 1 : 2))) continue;
      fm.linear_edge = cut_;
      const VectorXd a = deflection::wall_errors(model_, ws_, side, levels).error;
      fm.linear_edge = edge_;
      const VectorXd b = deflection::wall_errors(model_, ws_, side, levels).error;
      r.wall_c = std::min(r.wall_c, largest_linear(a, b, max_wall_error));
      r.wall_error = std::max(r.wall_error, (c0 * a + b).cwiseAbs().maxCoeff());
    }
  }
  return r;
}

}  // namespace netshape::compensation::detail
