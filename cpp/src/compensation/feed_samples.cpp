#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include "netshape/compensation/feed_schedule.hpp"
#include "netshape/core/error.hpp"
#include "netshape/core/progress.hpp"
#include "netshape/deflection/cantilever.hpp"
#include "netshape/force/ball_end_model.hpp"
#include "netshape/force/flat_end_model.hpp"
#include "netshape/stock/engagement.hpp"
#include "netshape/stock/sweep.hpp"

namespace netshape::compensation {

namespace {
constexpr double inf = std::numeric_limits<double>::infinity();
constexpr double two_pi = 2.0 * pi;

void check_limit(const char* field, double v, const char* unit) {
  NETSHAPE_CHECK(!std::isnan(v) && v > 0.0, field, v, (std::string("must be positive or inf ") + unit).c_str());
}
}  // namespace

const char* to_string(FeedLimit l) noexcept {
  switch (l) {
    case FeedLimit::force: return "max_force_N";
    case FeedLimit::chip: return "max_chip_mm";
    case FeedLimit::deflection: return "max_deflection_mm";
    case FeedLimit::wall_error: return "max_wall_error_mm";
    case FeedLimit::power: return "max_power_W";
    case FeedLimit::torque: return "max_torque_Nm";
    case FeedLimit::max_feed: return "max_feed_mm_min";
    case FeedLimit::air: return "air_feed_mm_min";
    case FeedLimit::programmed: return "programmed";
  }
  return "?";
}

void FeedLimits::validate() const {
  check_limit("max_force_N", max_force, "[N]");
  check_limit("max_chip_mm", max_chip, "[mm]");
  check_limit("max_deflection_mm", max_deflection, "[mm]");
  check_limit("max_wall_error_mm", max_wall_error, "[mm]");
  check_limit("max_power_W", max_power, "[W]");
  check_limit("max_torque_Nm", max_torque, "[N·m]");
  NETSHAPE_CHECK(std::isfinite(min_chip) && min_chip >= 0.0, "min_chip_mm", min_chip, "must be ≥ 0 [mm]");
  NETSHAPE_CHECK(min_chip < max_chip, "min_chip_mm", min_chip, "must be below max_chip_mm [mm]");
  NETSHAPE_CHECK(std::isfinite(min_feed) && min_feed >= 0.0, "min_feed", min_feed, "must be ≥ 0 [mm/s]");
  NETSHAPE_CHECK(std::isfinite(max_feed) && max_feed > min_feed, "max_feed", max_feed,
                 "must be finite and above min_feed [mm/s]");
  NETSHAPE_CHECK(std::isfinite(air_feed) && air_feed >= 0.0, "air_feed", air_feed, "must be ≥ 0 [mm/s]");
}

void FeedScheduleOptions::validate() const { sampling.validate(); }

namespace detail {

/// Largest c ≥ 0 with max_k |w ⊙ (c^p P_k + c^q Q_k)| ≤ limit (w selects components); 0 when even
/// c → 0 exceeds it, inf when no c does. p = 1, q = 0: the quadratic per angle; else bisection.
double largest_feed_per_tooth(const Points3& P, const Points3& Q, double p, double q, const Vec3& w,
                              double limit) {
  if (!std::isfinite(limit)) return inf;
  if (p == 1.0 && q == 0.0) {
    double best = inf;
    for (Eigen::Index k = 0; k < P.rows(); ++k) {
      const Vec3 a = P.row(k).transpose().cwiseProduct(w), b = Q.row(k).transpose().cwiseProduct(w);
      const double aa = a.squaredNorm(), ab = a.dot(b), cc = b.squaredNorm() - limit * limit;
      if (cc > 0.0) return 0.0;
      if (aa <= 0.0) continue;
      best = std::min(best, (-ab + std::sqrt(std::max(ab * ab - aa * cc, 0.0))) / aa);
    }
    return best;
  }
  auto peak = [&](double c) {
    const double cp = std::pow(c, p), cq = std::pow(c, q);
    double m = 0.0;
    for (Eigen::Index k = 0; k < P.rows(); ++k)
      m = std::max(m, (cp * P.row(k) + cq * Q.row(k)).transpose().cwiseProduct(w).norm());
    return m;
  };
  double lo = 0.0, hi = 1e-4;
  while (peak(hi) <= limit) {
    lo = hi;
    hi *= 2.0;
    if (hi > 1e3) return inf;
  }
  for (int it = 0; it < 60; ++it) {
    const double mid = 0.5 * (lo + hi);
    (peak(mid) <= limit ? lo : hi) = mid;
  }
  return lo;
}

/// Mean over the angles of Σ max(sin φ, 0)·dz and Σ dz over the engaged elements of a flat end mill
/// (the cutting and the edge part of Σ dF_t per unit ktc and kte), read from the map as the force
/// kernel reads it (bin = ⌊φ·bins/2π⌋).
void tangential_sums(const force::FlatEndWorkspace& ws, int flutes, double k_beta, const stock::MaskR& mask,
                     const VectorXd& angles, double& cutting, double& edge) {
  const int bins = static_cast<int>(mask.cols());
  const VectorXd& z = ws.heights();
  double sc = 0.0, se = 0.0;
  for (Eigen::Index a = 0; a < angles.size(); ++a)
    for (int i = 0; i < ws.disks(); ++i)
      for (int j = 0; j < flutes; ++j) {
        double ph = std::fmod(angles[a] + j * two_pi / flutes - k_beta * z[i], two_pi);
        if (ph < 0) ph += two_pi;
        const int b = std::min(bins - 1, static_cast<int>(ph * bins / two_pi));
        if (!mask(i, b)) continue;
        sc += std::max(std::sin(ph), 0.0);
        se += 1.0;
      }
  const double n = static_cast<double>(angles.size());
  cutting = sc * ws.disk_height() / n;
  edge = se * ws.disk_height() / n;
}

}  // namespace detail

namespace {

/// The two force parts at c = 1 of one sample (see the file comment of feed_schedule.hpp).
struct SampleForces {
  Points3 P, Q;
  double p = 1.0, q = 0.0;
  double torque_cutting = 0.0, torque_edge = 0.0;  // mean T = c·cutting + edge [N·mm]
};

/// What the engagement mask says: engaged, wall bits, depth, chip factor.
void read_mask(const stock::MaskR& mask, const VectorXd& phi, const VectorXd& z, double dz,
               std::vector<double>& row) {
  const Eigen::Index bins = mask.cols(), half = bins / 2;
  bool any = false, left = false, right = false;
  double depth = 0.0, chip = 0.0;
  for (Eigen::Index i = 0; i < mask.rows(); ++i)
    for (Eigen::Index b = 0; b < bins; ++b) {
      if (!mask(i, b)) continue;
      any = true;
      depth = std::max(depth, z[i] + 0.5 * dz);
      chip = std::max(chip, std::sin(phi[b]));
      left = left || b == 0 || b == bins - 1;
      right = right || b == half - 1 || b == half;
    }
  row = {any ? 1.0 : 0.0, (left ? 1.0 : 0.0) + (right ? 2.0 : 0.0), depth, chip};
}

}  // namespace

FeedSamples feed_samples(stock::ZMap& stock, const cutter::Cutter& cutter, const toolpath::Toolpath& program,
                         const force::ProgramCoefficients& k, const FeedLimits& limits,
                         const FeedScheduleOptions& options) {
  options.validate();
  limits.validate();
  cutter.validate();
  const force::ProgramForceOptions& opt = options.sampling;
  NETSHAPE_CHECK(cutter.kind != cutter::CutterKind::bull, "cutter.kind", "bull",
                 "feed scheduling models flat and ball end mills");
  const bool ball = cutter.kind == cutter::CutterKind::ball;
  if (ball) {
    k.ball_end.validate();
    NETSHAPE_CHECK(!std::isfinite(limits.max_power) && !std::isfinite(limits.max_torque), "max_power_W",
                   limits.max_power, "power and torque limits are modelled for flat end mills");
  } else {
    k.linear_edge.validate();
  }
  const double top = stock.max_height();
  VectorXd phi(opt.bins);
  for (int b = 0; b < opt.bins; ++b) phi[b] = (b + 0.5) * two_pi / opt.bins;
  const VectorXd angles = force::rotation_angles(opt.samples_per_revolution);
  const deflection::Cantilever beam = deflection::Cantilever::tool(
      cutter.diameter(), cutter.stick_out, cutter.youngs_modulus, deflection::InertiaModel::square);

  force::FlatEndModel fm;
  fm.radius = cutter.radius;
  fm.flutes = cutter.flutes;
  fm.helix = cutter.helix;
  fm.engagement = force::AngularEngagement{0.0, two_pi};
  fm.disk_height = opt.disk_height;
  fm.feed_per_tooth = 1.0;
  force::LinearEdgeCoefficients cut_part = k.linear_edge, edge_part = k.linear_edge;
  cut_part.kte = cut_part.kre = cut_part.kae = 0.0;
  edge_part.ktc = edge_part.krc = edge_part.kac = 0.0;
  force::BallEndModel bm;
  bm.radius = cutter.radius;
  bm.flutes = cutter.flutes;
  bm.helix = cutter.helix;
  bm.engagement = force::AngularEngagement{0.0, two_pi};
  bm.element_angle = opt.element_angle;
  bm.disk_height = opt.disk_height;
  bm.feed_per_tooth = 1.0;
  force::BallEndCoefficients tan_part = k.ball_end, rad_part = k.ball_end;
  tan_part.b = {0.0, 0.0, 0.0, 0.0};
  rad_part.a = {0.0, 0.0, 0.0, 0.0};
  force::FlatEndWorkspace fws;
  force::BallEndWorkspace bws;
  stock::MaskR mask;
  force::EngagementMap map;
  SampleForces sf;
  sf.P.resize(angles.size(), 3);
  sf.Q.resize(angles.size(), 3);
  if (ball) {
    sf.p = k.ball_end.m_t;
    sf.q = k.ball_end.m_r;
  }

  std::vector<Vec3> pos, dir;
  std::vector<int> blk;
  std::vector<double> frac, rpms, force_prog, lowest;
  std::vector<std::array<double, 4>> info;
  std::vector<std::array<double, feed_limit_columns>> allowed;
  std::vector<double> row;
  FeedSamples out;
  core::Progress progress("feeds", program.blocks.size());
  for (std::size_t bi = 0; bi < program.blocks.size(); ++bi) {
    progress.report(bi);
    const toolpath::Block& b = program.blocks[bi];
    const double len = b.length();
    if (len <= 0.0) continue;
    if (b.kind == toolpath::MotionKind::rapid) {
      out.removed_volume += stock::sweep_line(stock, cutter, b.start, b.end).removed_volume;
      continue;
    }
    const int n = std::max(1, static_cast<int>(std::ceil(len / opt.step - 1e-9)));
    Vec3 prev = b.start;
    for (int s = 1; s <= n; ++s) {
      const double sd = static_cast<double>(s) / n;
      const Vec3 p = b.point_at(sd);
      const Vec3 t = b.tangent_at(sd);
      const Vec3 th(t.x(), t.y(), 0.0);
      const double depth = std::min(cutter.flute_length, top - p.z());
      if (th.norm() > 1e-9 && depth > 0.0) {
        const double rpm = opt.spindle_rpm > 0 ? opt.spindle_rpm : std::abs(b.spindle_rpm);
        const Vec3 fd = th.normalized();
        const VectorXd* z = nullptr;
        double dz = 0.0;
        if (ball) {
          bm.axial_depth = std::max(depth, 1e-3);
          bm.inclination = std::clamp(std::atan2(t.z(), th.norm()), -deg2rad(79.0), deg2rad(79.0));
          bws.reset(bm);
          z = &bws.heights();
          dz = opt.disk_height;
        } else {
          fm.axial_depth = std::max(depth, 1e-3);
          if (fws.disks() != fm.disks() || std::abs(fws.disk_height() * fws.disks() - fm.axial_depth) > 1e-12)
            fws.reset(fm);
          z = &fws.heights();
          dz = fws.disk_height();
        }
        stock::engaged_elements_into(stock, cutter, p, fd, phi, *z, mask);
        read_mask(mask, phi, *z, dz, row);
        std::array<double, feed_limit_columns> al;
        al.fill(inf);
        double low = 0.0, fprog = 0.0;
        if (row[0] > 0.0) {
          NETSHAPE_CHECK(rpm > 0.0, ("block at line " + std::to_string(b.line) + ": spindle_rpm").c_str(), rpm,
                         "a cutting move needs a spindle speed (S word) [rev/min]");
          map.mask = mask.cast<std::uint8_t>();
          if (ball) {
            bm.coefficients = tan_part;
            force::ball_end_forces(bm, bws, angles, sf.P, &map);
            bm.coefficients = rad_part;
            force::ball_end_forces(bm, bws, angles, sf.Q, &map);
          } else {
            fm.linear_edge = cut_part;
            force::flat_end_forces(fm, fws, angles, sf.P, &map);
            fm.linear_edge = edge_part;
            force::flat_end_forces(fm, fws, angles, sf.Q, &map);
            double tc = 0.0, te = 0.0;
            detail::tangential_sums(fws, cutter.flutes, fm.k_beta(), mask, angles, tc, te);
            sf.torque_cutting = cutter.radius * k.linear_edge.ktc * tc;
            sf.torque_edge = cutter.radius * k.linear_edge.kte * te;
          }
          const double to_feed = cutter.flutes * rpm / 60.0;  // mm/s per mm/tooth
          const double a = std::min(row[2], beam.length);
          const double kappa = beam.influence(beam.length, beam.length - 0.5 * a) + cutter.holder_compliance;
          const Vec3 all(1, 1, 1), xy(1, 1, 0), y(0, 1, 0);
          auto feed_of = [&](double c) { return c * to_feed; };
          al[0] = feed_of(detail::largest_feed_per_tooth(sf.P, sf.Q, sf.p, sf.q, all, limits.max_force));
          if (row[3] > 0.0) al[1] = feed_of(limits.max_chip / row[3]);
          al[2] = feed_of(detail::largest_feed_per_tooth(sf.P, sf.Q, sf.p, sf.q, xy, limits.max_deflection / kappa));
          if (row[1] > 0.0)
            al[3] = feed_of(detail::largest_feed_per_tooth(sf.P, sf.Q, sf.p, sf.q, y, limits.max_wall_error / kappa));
          if (!ball) {
            const double omega = two_pi * rpm / 60.0;
            auto torque_feed = [&](double t_nmm) {
              if (!std::isfinite(t_nmm)) return inf;
              if (sf.torque_edge >= t_nmm) return 0.0;
              return sf.torque_cutting > 0 ? feed_of((t_nmm - sf.torque_edge) / sf.torque_cutting) : inf;
            };
            al[4] = torque_feed(limits.max_power / omega * 1e3);
            al[5] = torque_feed(limits.max_torque * 1e3);
          }
          if (row[3] > 0.0) low = feed_of(limits.min_chip / row[3]);
          const double c0 = rpm > 0 ? b.feed / to_feed : 0.0;
          const double cp = std::pow(c0, sf.p), cq = std::pow(c0, sf.q);
          for (Eigen::Index i = 0; i < angles.size(); ++i)
            fprog = std::max(fprog, (cp * sf.P.row(i) + cq * sf.Q.row(i)).norm());
        }
        pos.push_back(p);
        dir.push_back(fd);
        blk.push_back(static_cast<int>(bi));
        frac.push_back(sd);
        rpms.push_back(rpm);
        info.push_back({row[0], row[1], row[2], row[3]});
        allowed.push_back(al);
        lowest.push_back(low);
        force_prog.push_back(fprog);
      }
      out.removed_volume += stock::sweep_line(stock, cutter, prev, p).removed_volume;
      prev = p;
    }
  }
  const Eigen::Index m = static_cast<Eigen::Index>(pos.size());
  out.positions.resize(m, 3);
  out.feed_direction.resize(m, 3);
  out.block.resize(m);
  out.fraction.resize(m);
  out.spindle_rpm.resize(m);
  out.engaged.resize(m);
  out.walls.resize(m);
  out.depth.resize(m);
  out.chip_factor.resize(m);
  out.allowed.resize(m, feed_limit_columns);
  out.lowest.resize(m);
  out.force.resize(m);
  for (Eigen::Index i = 0; i < m; ++i) {
    out.positions.row(i) = pos[i].transpose();
    out.feed_direction.row(i) = dir[i].transpose();
    out.block[i] = blk[i];
    out.fraction[i] = frac[i];
    out.spindle_rpm[i] = rpms[i];
    out.engaged[i] = static_cast<int>(info[i][0]);
    out.walls[i] = static_cast<int>(info[i][1]);
    out.depth[i] = info[i][2];
    out.chip_factor[i] = info[i][3];
    for (int j = 0; j < feed_limit_columns; ++j) out.allowed(i, j) = allowed[i][j];
    out.lowest[i] = lowest[i];
    out.force[i] = force_prog[i];
  }
  return out;
}

}  // namespace netshape::compensation
