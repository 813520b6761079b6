#include "netshape/force/ball_end_model.hpp"

#include <algorithm>
#include <cmath>

#include "netshape/core/error.hpp"
#include "netshape/cutter/cutter.hpp"

namespace netshape::force {

namespace {
constexpr double two_pi = 2.0 * pi;
inline double wrap(double a) { return a - two_pi * std::floor(a / two_pi); }
}  // namespace

void BallEndModel::validate() const {
  NETSHAPE_CHECK_FINITE("radius", radius);
  NETSHAPE_CHECK(radius > 0.0, "radius", radius, "must be positive [mm]");
  cutter::check_flutes(flutes);
  NETSHAPE_CHECK_FINITE("helix", helix);
  NETSHAPE_CHECK(helix >= 0.0 && helix < deg2rad(85.0), "helix", helix, "must be in [0, 85°) [rad]");
  NETSHAPE_CHECK_FINITE("axial_depth", axial_depth);
  NETSHAPE_CHECK(axial_depth > 0.0, "axial_depth", axial_depth, "must be positive [mm]");
  NETSHAPE_CHECK(axial_depth <= 100.0 * radius, "axial_depth", axial_depth, "must be at most 100 R [mm]");
  NETSHAPE_CHECK_FINITE("feed_per_tooth", feed_per_tooth);
  NETSHAPE_CHECK(feed_per_tooth >= 0.0, "feed_per_tooth", feed_per_tooth, "must be ≥ 0 [mm]");
  NETSHAPE_CHECK_FINITE("inclination", inclination);
  NETSHAPE_CHECK(std::abs(inclination) < deg2rad(80.0), "inclination", inclination,
                 "must be in (−80°, 80°) [rad]");
  NETSHAPE_CHECK_FINITE("element_angle", element_angle);
  NETSHAPE_CHECK(element_angle > 1e-5 && element_angle <= 0.5, "element_angle", element_angle,
                 "must be in (1e-5, 0.5] [rad]");
  NETSHAPE_CHECK_FINITE("disk_height", disk_height);
  NETSHAPE_CHECK(disk_height > 0.0 && axial_depth / disk_height <= 1e6, "disk_height", disk_height,
                 "must be positive and give at most 1e6 disks [mm]");
  NETSHAPE_CHECK_FINITE("runout_rho", runout_rho);
  NETSHAPE_CHECK(runout_rho >= 0.0 && runout_rho < radius, "runout_rho", runout_rho,
                 "must be in [0, R) [mm]");
  NETSHAPE_CHECK_FINITE("runout_lambda", runout_lambda);
  engagement.validate();
  coefficients.validate();
}

double BallEndModel::k_beta() const { return std::tan(helix) / radius; }

void BallEndWorkspace::reset(const BallEndModel& model) {
  model.validate();
  flutes_ = model.flutes;
  radius_ = model.radius;
  helix_ = model.helix;
  depth_ = model.axial_depth;
  xi_ = model.inclination;
  dpsi_target_ = model.element_angle;
  dz_target_ = model.disk_height;
  const double R = model.radius;
  const bool tilted = model.inclination != 0.0;
  const double zmax = tilted ? model.axial_depth + 2.0 * R * std::abs(std::sin(model.inclination))
                             : model.axial_depth;
  const double psi_lo = zmax >= R ? 0.0 : std::asin(1.0 - zmax / R);
  const int nb = std::max(1, static_cast<int>(std::ceil((0.5 * pi - psi_lo) / model.element_angle - 1e-9)));
  const double dpsi = (0.5 * pi - psi_lo) / nb;
  const int nc = zmax > R ? std::max(1, static_cast<int>(std::ceil((zmax - R) / model.disk_height - 1e-9))) : 0;
  const double dz = nc ? (zmax - R) / nc : 0.0;
  const int rows = nb + nc;
  z_.resize(rows);
  r_.resize(rows);
  psi_.resize(rows);
  step_.resize(rows);
  w0_.resize(rows);
  is_ball_.resize(rows);
  kt_.resize(rows);
  kr_.resize(rows);
  cos_psi_.resize(rows);
  runout_step_.resize(flutes_);
  // ball rows from the tip upwards, then the cylinder
  for (int k = 0; k < nb; ++k) {
    const double psi = 0.5 * pi - (k + 0.5) * dpsi;
    psi_[k] = psi;
    z_[k] = R * (1.0 - std::sin(psi));
    r_[k] = R * std::cos(psi);
    step_[k] = dpsi;
    is_ball_[k] = 1;
    w0_[k] = r_[k] * dpsi;
  }
  for (int i = 0; i < nb; ++i) cos_psi_[i] = std::cos(psi_[i]);
  for (int k = 0; k < nc; ++k) {
    const int i = nb + k;
    cos_psi_[i] = 1.0;
    psi_[i] = 0.0;
    z_[i] = R + (k + 0.5) * dz;
    r_[i] = R;
    step_[i] = dz;
    is_ball_[i] = 0;
    w0_[i] = dz;
  }
}

void ball_end_forces(const BallEndModel& model, BallEndWorkspace& ws, const Eigen::Ref<const VectorXd>& angles,
                     Eigen::Ref<Points3> out, const EngagementMap* map) {
  NETSHAPE_CHECK(out.rows() == angles.size(), "out.rows", out.rows(), "must equal the number of angles");
  if (ws.flutes_ != model.flutes || ws.radius_ != model.radius || ws.helix_ != model.helix ||
      ws.depth_ != model.axial_depth || ws.xi_ != model.inclination || ws.dpsi_target_ != model.element_angle ||
      ws.dz_target_ != model.disk_height)
    ws.reset(model);
  else
    model.validate();
  if (map)
    NETSHAPE_CHECK(map->disks() == ws.rows() && map->bins() >= 4, "engagement_map.rows", map->disks(),
                   "must equal the rows of the ball-end workspace (and have at least 4 bins)");
  for (Eigen::Index k = 0; k < angles.size(); ++k) NETSHAPE_CHECK_FINITE("angles", angles[k]);

  const BallEndCoefficients& K = model.coefficients;
  const int rows = ws.rows();
  for (int i = 0; i < rows; ++i) {
    ws.kt_[i] = K.kt(ws.psi_[i]);
    ws.kr_[i] = K.kr(ws.psi_[i]);
  }
  const bool runout = model.runout_rho != 0.0;
  for (int j = 0; j < ws.flutes_; ++j) {  // r_j − r_{j+1}: flute j + 1 passed each angle just before j
    const int jp = (j + 1) % ws.flutes_;
    ws.runout_step_[j] = model.runout_rho * (std::cos(model.runout_lambda - two_pi * j / ws.flutes_) -
                                             std::cos(model.runout_lambda - two_pi * jp / ws.flutes_));
  }
  const double R = model.radius;
  const double f = model.feed_per_tooth;
  const double kb = model.k_beta();
  const double cx = std::cos(model.inclination), sx = std::sin(model.inclination);
  const double st = model.engagement.phi_st;
  const double span = model.engagement.phi_ex - model.engagement.phi_st;
  const double ap = model.axial_depth * (1.0 + 1e-12);
  const int N = ws.flutes_;
  const int bins = map ? map->bins() : 0;
  for (Eigen::Index a = 0; a < angles.size(); ++a) {
    double fx = 0.0, fy = 0.0;
    for (int i = 0; i < rows; ++i) {
      const double r = ws.r_[i], zc = ws.z_[i] - R;
      for (int j = 0; j < N; ++j) {
        const double ph = wrap(angles[a] + j * two_pi / N - kb * ws.z_[i]);
        const double sp = std::sin(ph), cp = std::cos(ph);
        const double X = r * sp, Y = r * cp;
        const double Xp = X * cx + zc * sx;          // along the inclined feed
        const double Zp = -X * sx + zc * cx;         // along the inclined axis, from the ball centre
        if (Xp <= 0.0 || Zp + R > ap) continue;      // behind the cutter or above the cut
        bool in;
        if (map) {  // material map in the cutter plane: tool-frame immersion
          int b = static_cast<int>(ph * bins / two_pi);
          b = b >= bins ? bins - 1 : b;
          in = map->mask(i, b) != 0;
        } else {  // straight walls parallel to the feed (see the header): the element cuts where the
                  // point of the largest circle (radius R) at its own distance Y from the feed line,
                  // on the front half, lies in the window
          const double az = std::acos(std::clamp(Y / R, -1.0, 1.0));  // in [0, π]
          double u = az - st;
          u = u < 0.0 ? u + two_pi : u;
          in = u <= span;
        }
        if (!in) continue;
        const double rho = std::sqrt(Xp * Xp + Y * Y);  // R cos φ'
        double t = f * Xp / rho;                        // chip f sin ϕ [mm]
        if (runout) t += ws.runout_step_[j] * ws.cos_psi_[i];  // the flute's step along the normal
        if (t <= 0.0) continue;
        const double dw = ws.is_ball_[i] ? rho * ws.step_[i] : ws.step_[i];
        const double lt = std::log(t);
        const double dFt = ws.kt_[i] * std::exp(K.m_t * lt) * dw;
        const double dFr = ws.kr_[i] * std::exp(K.m_r * lt) * dw;
        fx += -dFt * cp - dFr * sp;
        fy += dFt * sp - dFr * cp;
      }
    }
    out(a, 0) = fx;
    out(a, 1) = fy;
    out(a, 2) = 0.0;
  }
}

Points3 ball_end_forces(const BallEndModel& model, const Eigen::Ref<const VectorXd>& angles) {
  BallEndWorkspace ws(model);
  Points3 out(angles.size(), 3);
  ball_end_forces(model, ws, angles, out);
  return out;
}

Points3 ball_end_forces(const BallEndModel& model, const Eigen::Ref<const VectorXd>& angles,
                        const EngagementMap& map) {
  BallEndWorkspace ws(model);
  Points3 out(angles.size(), 3);
  ball_end_forces(model, ws, angles, out, &map);
  return out;
}

}  // namespace netshape::force
