#include "netshape/force/flat_end_model.hpp"

#include <algorithm>
#include <cmath>

#include "netshape/core/error.hpp"
#include "netshape/cutter/cutter.hpp"

#include "force/kernels/flat_end_kernels.hpp"

namespace netshape::force {

namespace {
constexpr double two_pi = 2.0 * pi;

// The element loop of the instruction set chosen for this process (core/dispatch.hpp).
const kernels::FlatEndKernels& flat_end_kernels() {
  static const kernels::FlatEndKernels& k = NETSHAPE_SIMD_SELECT(kernels, flat_end_kernels);
  return k;
}
}  // namespace

void FlatEndModel::validate() const {
  NETSHAPE_CHECK_FINITE("radius", radius);
  NETSHAPE_CHECK(radius > 0.0, "radius", radius, "must be positive [mm]");
  cutter::check_flutes(flutes);
  NETSHAPE_CHECK_FINITE("helix", helix);
  NETSHAPE_CHECK(helix >= 0.0 && helix < deg2rad(85.0), "helix", helix, "must be in [0, 85°) [rad]");
  NETSHAPE_CHECK_FINITE("axial_depth", axial_depth);
  NETSHAPE_CHECK(axial_depth > 0.0, "axial_depth", axial_depth, "must be positive [mm]");
  NETSHAPE_CHECK_FINITE("feed_per_tooth", feed_per_tooth);
  NETSHAPE_CHECK(feed_per_tooth >= 0.0, "feed_per_tooth", feed_per_tooth, "must be ≥ 0 [mm]");
  NETSHAPE_CHECK_FINITE("disk_height", disk_height);
  NETSHAPE_CHECK(disk_height > 0.0, "disk_height", disk_height, "must be positive [mm]");
  NETSHAPE_CHECK(axial_depth / disk_height <= 1e6, "disk_height", disk_height,
                 "gives more than 1e6 disks over the axial depth");
  engagement.validate();
  if (coefficient_model == FlatCoefficientModel::linear_edge)
    linear_edge.validate();
  else
    kline_devor.validate();
}

int FlatEndModel::disks() const {
  return std::max(1, static_cast<int>(std::ceil(axial_depth / disk_height - 1e-9)));
}

double FlatEndModel::k_beta() const { return std::tan(helix) / radius; }

void FlatEndWorkspace::reset(const FlatEndModel& model) {
  model.validate();
  disks_ = model.disks();
  flutes_ = model.flutes;
  dz_ = model.axial_depth / disks_;
  radius_ = model.radius;
  helix_ = model.helix;
  depth_ = model.axial_depth;
  target_dz_ = model.disk_height;
  const int n = disks_ * flutes_;
  z_.resize(disks_);
  off_.resize(n);
  cos_off_.resize(n);
  sin_off_.resize(n);
  disk_of_.resize(n);
  const double kb = model.k_beta();
  for (int i = 0; i < disks_; ++i) {
    z_[i] = (i + 0.5) * dz_;
    for (int j = 0; j < flutes_; ++j) {
      const int e = i * flutes_ + j;
      const double o = j * two_pi / flutes_ - kb * z_[i];
      off_[e] = kernels::wrap_angle(o);
      cos_off_[e] = std::cos(o);
      sin_off_[e] = std::sin(o);
      disk_of_[e] = i;
    }
  }
}

void flat_end_forces(const FlatEndModel& model, FlatEndWorkspace& ws, const Eigen::Ref<const VectorXd>& angles,
                     Eigen::Ref<Points3> out, const EngagementMap* map) {
  NETSHAPE_CHECK(out.rows() == angles.size(), "out.rows", out.rows(), "must equal the number of angles");
  if (ws.disks_ != model.disks() || ws.flutes_ != model.flutes || ws.radius_ != model.radius ||
      ws.helix_ != model.helix || ws.depth_ != model.axial_depth || ws.target_dz_ != model.disk_height)
    ws.reset(model);  // geometry changed: rebuild (allocates only then)
  else {
    model.engagement.validate();
    NETSHAPE_CHECK_FINITE("feed_per_tooth", model.feed_per_tooth);
    NETSHAPE_CHECK(model.feed_per_tooth >= 0.0, "feed_per_tooth", model.feed_per_tooth, "must be ≥ 0 [mm]");
    if (model.coefficient_model == FlatCoefficientModel::linear_edge)
      model.linear_edge.validate();
    else
      model.kline_devor.validate();
  }
  if (map) {
    NETSHAPE_CHECK(map->disks() == ws.disks_, "engagement_map.rows", map->disks(),
                   "must equal the number of disks of the model");
    NETSHAPE_CHECK(map->bins() >= 4, "engagement_map.cols", map->bins(), "must be at least 4 bins");
  }
  for (Eigen::Index k = 0; k < angles.size(); ++k)
    NETSHAPE_CHECK_FINITE("angles", angles[k]);

  const int n = ws.elements();
  const double c = model.feed_per_tooth;
  const double dz = ws.dz_;
  const double st = model.engagement.phi_st;
  const double span = model.engagement.phi_ex - model.engagement.phi_st;
  const bool kd = model.coefficient_model == FlatCoefficientModel::kline_devor;
  const LinearEdgeCoefficients k = model.linear_edge;
  const double KT = model.kline_devor.kt, KR = model.kline_devor.kr;
  const int bins = map ? map->bins() : 0;
  const double bin_scale = map ? bins / two_pi : 0.0;

  const kernels::ElementArrays arr{ws.off_.data(), ws.cos_off_.data(), ws.sin_off_.data(), ws.disk_of_.data()};
  const kernels::LoopConstants lc{n,    c,  dz, st, span, k, KT, KR, map ? map->mask.data() : nullptr,
                         map ? static_cast<Eigen::Index>(map->mask.outerStride()) : 0,
                         bins, bin_scale};
  const double* th = angles.data();
  const Eigen::Index count = angles.size();
  double* o = out.data();
  const Eigen::Index os = out.outerStride();
  flat_end_kernels().loop[map != nullptr][kd](lc, arr, th, count, o, os);
}

Points3 flat_end_forces(const FlatEndModel& model, const Eigen::Ref<const VectorXd>& angles) {
  FlatEndWorkspace ws(model);
  Points3 out(angles.size(), 3);
  flat_end_forces(model, ws, angles, out);
  return out;
}

Points3 flat_end_forces(const FlatEndModel& model, const Eigen::Ref<const VectorXd>& angles,
                        const EngagementMap& map) {
  FlatEndWorkspace ws(model);
  Points3 out(angles.size(), 3);
  flat_end_forces(model, ws, angles, out, &map);
  return out;
}

VectorXd rotation_angles(int count, double revolutions) {
  NETSHAPE_CHECK(count >= 1, "count", count, "must be at least 1");
  NETSHAPE_CHECK_FINITE("revolutions", revolutions);
  NETSHAPE_CHECK(revolutions > 0.0, "revolutions", revolutions, "must be positive");
  VectorXd a(count);
  for (int k = 0; k < count; ++k) a[k] = two_pi * revolutions * k / count;
  return a;
}

}  // namespace netshape::force

namespace netshape::force {

void flat_end_moments(const FlatEndModel& model, FlatEndWorkspace& ws, const Eigen::Ref<const VectorXd>& angles,
                      Eigen::Ref<MatrixXdR> out) {
  NETSHAPE_CHECK(out.rows() == angles.size() && out.cols() == 6, "out.rows", out.rows(),
                 "must be (number of angles, 6)");
  ws.reset(model);
  for (Eigen::Index k = 0; k < angles.size(); ++k) NETSHAPE_CHECK_FINITE("angles", angles[k]);
  const int n = ws.elements();
  const double c = model.feed_per_tooth, dz = ws.dz_;
  const double st = model.engagement.phi_st;
  const double span = model.engagement.phi_ex - model.engagement.phi_st;
  for (Eigen::Index a = 0; a < angles.size(); ++a) {
    const double th = angles[a];
    const double thw = kernels::wrap_angle(th);
    const double s0 = std::sin(th), c0 = std::cos(th);
    double m0 = 0, m1 = 0, m2 = 0, m3 = 0, m4 = 0, m5 = 0;
    for (int e = 0; e < n; ++e) {
      double ph = thw + ws.off_[e];
      ph = ph >= two_pi ? ph - two_pi : ph;
      double u = ph - st;
      u = u < 0.0 ? u + two_pi : u;
      if (u > span) continue;
      const double sp = s0 * ws.cos_off_[e] + c0 * ws.sin_off_[e];
      const double cp = c0 * ws.cos_off_[e] - s0 * ws.sin_off_[e];
      const double h = std::max(c * sp, 0.0);
      m0 += h * cp;
      m1 += h * sp;
      m2 += h;
      m3 += cp;
      m4 += sp;
      m5 += 1.0;
    }
    out(a, 0) = m0 * dz;
    out(a, 1) = m1 * dz;
    out(a, 2) = m2 * dz;
    out(a, 3) = m3 * dz;
    out(a, 4) = m4 * dz;
    out(a, 5) = m5 * dz;
  }
}

}  // namespace netshape::force
