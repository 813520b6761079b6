#include "netshape/force/program.hpp"

#include <algorithm>
#include <cmath>

#include "netshape/core/error.hpp"
#include "netshape/force/ball_end_model.hpp"
#include "netshape/force/engagement.hpp"
#include "netshape/force/flat_end_model.hpp"
#include "netshape/force/force_summary.hpp"
#include "netshape/force/program_walk.hpp"
#include "netshape/force/runout_size_effect.hpp"
#include "netshape/stock/engagement.hpp"

namespace netshape::force {

void ProgramForceOptions::validate() const {
  NETSHAPE_CHECK_FINITE("step", step);
  NETSHAPE_CHECK(step > 0.0, "step", step, "must be positive [mm]");
  NETSHAPE_CHECK(samples_per_revolution >= 8, "samples_per_revolution", samples_per_revolution, "must be ≥ 8");
  NETSHAPE_CHECK(bins >= 8, "bins", bins, "must be ≥ 8");
  NETSHAPE_CHECK(disk_height > 0.0 && std::isfinite(disk_height), "disk_height", disk_height, "must be positive [mm]");
  NETSHAPE_CHECK(element_angle > 0.0 && element_angle <= 0.5, "element_angle", element_angle, "must be in (0, 0.5] [rad]");
  NETSHAPE_CHECK(feed_per_tooth >= 0.0 && std::isfinite(feed_per_tooth), "feed_per_tooth", feed_per_tooth,
                 "must be ≥ 0 (0: from the blocks) [mm]");
  NETSHAPE_CHECK(spindle_rpm >= 0.0 && std::isfinite(spindle_rpm), "spindle_rpm", spindle_rpm,
                 "must be ≥ 0 (0: from the blocks) [rev/min]");
}

ProgramForces simulate_program(stock::ZMap& stock, const cutter::Cutter& cutter, const toolpath::Toolpath& program,
                               const ProgramCoefficients& k, const ProgramForceOptions& opt) {
  opt.validate();
  cutter.validate();
  NETSHAPE_CHECK(cutter.kind != cutter::CutterKind::bull, "cutter.kind", "bull",
                 "force along a program models flat and ball end mills");
  const bool ball = cutter.kind == cutter::CutterKind::ball;
  if (ball) k.ball_end.validate(); else k.linear_edge.validate();
  k.chip.validate();
  NETSHAPE_CHECK(!ball || k.chip.chip_exponent == 1.0, "chip.chip_exponent", k.chip.chip_exponent,
                 "a ball end mill's chip-size effect is its Feng–Menq exponents m_T, m_R (must be 1 here)");
  const int bins = opt.bins;
  VectorXd phi(bins);
  for (int b = 0; b < bins; ++b) phi[b] = (b + 0.5) * 2.0 * pi / bins;
  const VectorXd angles = rotation_angles(opt.samples_per_revolution);
  Points3 F(angles.size(), 3);
  stock::MaskR mask;
  EngagementMap map;

  FlatEndModel fm;
  fm.radius = cutter.radius;
  fm.flutes = cutter.flutes;
  fm.helix = cutter.helix;
  fm.engagement = AngularEngagement{0.0, 2.0 * pi};
  fm.linear_edge = k.linear_edge;
  fm.disk_height = opt.disk_height;
  BallEndModel bm;
  bm.radius = cutter.radius;
  bm.flutes = cutter.flutes;
  bm.helix = cutter.helix;
  bm.engagement = AngularEngagement{0.0, 2.0 * pi};
  bm.coefficients = k.ball_end;
  bm.element_angle = opt.element_angle;
  bm.disk_height = opt.disk_height;
  bm.runout_rho = k.chip.runout_rho;  // ball_end_model.hpp: the runout step along the element normal
  bm.runout_lambda = k.chip.runout_lambda;
  FlatEndWorkspace fws;
  BallEndWorkspace bws;

  std::vector<Vec3> pos, dir, mean, peak;
  std::vector<int> blk;
  std::vector<double> pr, mr, frac;
  ProgramForces out;
  auto visit = [&](const WalkSample& w) {
    const toolpath::Block& b = program.blocks[w.block];
    const double rpm = opt.spindle_rpm > 0 ? opt.spindle_rpm : std::abs(b.spindle_rpm);
    const double c = opt.feed_per_tooth > 0 ? opt.feed_per_tooth
                                            : (rpm > 0 ? b.feed * 60.0 / (rpm * cutter.flutes) : 0.0);
    if (c <= 0.0) return;
    const VectorXd* z = nullptr;
    if (ball) {
      bm.axial_depth = std::max(w.depth, 1e-3);
      bm.feed_per_tooth = c;
      const double th = std::hypot(w.tangent.x(), w.tangent.y());
      bm.inclination = std::clamp(std::atan2(w.tangent.z(), th), -deg2rad(79.0), deg2rad(79.0));
      bws.reset(bm);
      z = &bws.heights();
    } else {
      fm.axial_depth = std::max(w.depth, 1e-3);
      fm.feed_per_tooth = c;
      if (fws.disks() != fm.disks() || std::abs(fws.disk_height() * fws.disks() - fm.axial_depth) > 1e-12)
        fws.reset(fm);
      z = &fws.heights();
    }
    stock::engaged_elements_into(stock, cutter, w.tip, w.feed_direction, phi, *z, mask);
    map.mask = mask.cast<std::uint8_t>();
    if (ball)
      ball_end_forces(bm, bws, angles, F, &map);
    else if (k.chip.none())
      flat_end_forces(fm, fws, angles, F, &map);
    else
      flat_end_forces_extended(fm, k.chip, fws, angles, F, map);
    const ForceSummary sm = summarize(F);
    pos.push_back(w.tip);
    dir.push_back(w.feed_direction);
    blk.push_back(static_cast<int>(w.block));
    mean.push_back(sm.mean);
    peak.push_back(sm.peak);
    pr.push_back(sm.peak_resultant);
    mr.push_back(sm.mean_resultant);
    frac.push_back(map.mask.size() ? map.mask.cast<double>().mean() : 0.0);
  };
  out.removed_volume = walk_program(stock, cutter, program, opt.step, visit, "forces");
  const Eigen::Index m = static_cast<Eigen::Index>(pos.size());
  out.positions.resize(m, 3);
  out.feed_direction.resize(m, 3);
  out.mean.resize(m, 3);
  out.peak.resize(m, 3);
  out.block.resize(m);
  out.peak_resultant.resize(m);
  out.mean_resultant.resize(m);
  out.engaged_fraction.resize(m);
  for (Eigen::Index i = 0; i < m; ++i) {
    out.positions.row(i) = pos[i].transpose();
    out.feed_direction.row(i) = dir[i].transpose();
    out.mean.row(i) = mean[i].transpose();
    out.peak.row(i) = peak[i].transpose();
    out.block[i] = blk[i];
    out.peak_resultant[i] = pr[i];
    out.mean_resultant[i] = mr[i];
    out.engaged_fraction[i] = frac[i];
  }
  return out;
}

}  // namespace netshape::force
