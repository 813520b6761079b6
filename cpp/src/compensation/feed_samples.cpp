#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <optional>
#include <string>
#include <vector>

#include "netshape/compensation/feed_schedule.hpp"
#include "netshape/core/error.hpp"
#include "netshape/deflection/cantilever.hpp"
#include "netshape/force/ball_end_model.hpp"
#include "netshape/force/flat_end_model.hpp"
#include "netshape/force/program_walk.hpp"
#include "netshape/stock/engagement.hpp"
#include "compensation/feed_deflection.hpp"

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
  return largest_below(peak, limit);
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

/// What the engagement mask says about one sample.
struct MaskFacts {
  bool engaged = false;
  int walls = 0;          // bit 1 left (within 10° of φ = 0), bit 2 right (within 10° of φ = π)
  double depth = 0.0;     // [mm]
  double chip = 0.0;      // max sin φ over the engaged bins
  double share = 0.0;     // engaged entries / all entries
};

MaskFacts read_mask(const stock::MaskR& mask, const VectorXd& phi, const VectorXd& z, double dz) {
  const Eigen::Index bins = mask.cols(), half = bins / 2;
  const Eigen::Index near = std::max<Eigen::Index>(1, bins / 36);  // bins within 10° of a wall angle
  MaskFacts f;
  Eigen::Index count = 0;
  for (Eigen::Index i = 0; i < mask.rows(); ++i)
    for (Eigen::Index b = 0; b < bins; ++b) {
      if (!mask(i, b)) continue;
      ++count;
      f.depth = std::max(f.depth, z[i] + 0.5 * dz);
      f.chip = std::max(f.chip, std::sin(phi[b]));
      if (b < near || b >= bins - near) f.walls |= 1;
      if (b >= half - near && b < half + near) f.walls |= 2;
    }
  f.engaged = count > 0;
  f.share = mask.size() ? static_cast<double>(count) / static_cast<double>(mask.size()) : 0.0;
  return f;
}

/// The force models of a program run with their two parts (file comment of feed_schedule.hpp), the
/// workspaces and the buffers: the sample loop allocates only when the cut depth changes.
class SampleForces {
 public:
  SampleForces(const cutter::Cutter& cutter, const force::ProgramCoefficients& k,
               const force::ProgramForceOptions& opt, Eigen::Index angles)
      : ball_(cutter.kind == cutter::CutterKind::ball), radius_(cutter.radius), k_(k) {
    fm_.radius = bm_.radius = cutter.radius;
    fm_.flutes = bm_.flutes = cutter.flutes;
    fm_.helix = bm_.helix = cutter.helix;
    fm_.engagement = bm_.engagement = force::AngularEngagement{0.0, two_pi};
    fm_.disk_height = bm_.disk_height = opt.disk_height;
    fm_.feed_per_tooth = bm_.feed_per_tooth = 1.0;
    bm_.element_angle = opt.element_angle;
    cut_ = edge_ = k.linear_edge;
    cut_.kte = cut_.kre = cut_.kae = 0.0;
    edge_.ktc = edge_.krc = edge_.kac = 0.0;
    tan_ = rad_ = k.ball_end;
    tan_.b = {0.0, 0.0, 0.0, 0.0};
    rad_.a = {0.0, 0.0, 0.0, 0.0};
    if (ball_) {
      p = k.ball_end.m_t;
      q = k.ball_end.m_r;
    }
    P.resize(angles, 3);
    Q.resize(angles, 3);
  }

  /// Element heights (and their spacing dz [mm]) for a cut `depth` [mm] with tangent `t`.
  const VectorXd& heights(double depth, const Vec3& t, double& dz) {
    if (ball_) {
      bm_.axial_depth = std::max(depth, 1e-3);
      const double th = std::hypot(t.x(), t.y());
      bm_.inclination = std::clamp(std::atan2(t.z(), th), -deg2rad(79.0), deg2rad(79.0));
      bws_.reset(bm_);
      dz = bm_.disk_height;
      return bws_.heights();
    }
    fm_.axial_depth = std::max(depth, 1e-3);
    if (fws_.disks() != fm_.disks() || std::abs(fws_.disk_height() * fws_.disks() - fm_.axial_depth) > 1e-12)
      fws_.reset(fm_);
    dz = fws_.disk_height();
    return fws_.heights();
  }

  /// P, Q at the angles for the engagement `mask`; flat: the mean torque parts too.
  void evaluate(const stock::MaskR& mask, const VectorXd& angles) {
    map_.mask = mask.cast<std::uint8_t>();
    if (ball_) {
      bm_.coefficients = tan_;
      force::ball_end_forces(bm_, bws_, angles, P, &map_);
      bm_.coefficients = rad_;
      force::ball_end_forces(bm_, bws_, angles, Q, &map_);
      return;
    }
    fm_.linear_edge = cut_;
    force::flat_end_forces(fm_, fws_, angles, P, &map_);
    fm_.linear_edge = edge_;
    force::flat_end_forces(fm_, fws_, angles, Q, &map_);
    double tc = 0.0, te = 0.0;
    detail::tangential_sums(fws_, fm_.flutes, fm_.k_beta(), mask, angles, tc, te);
    torque_cutting = radius_ * k_.linear_edge.ktc * tc;
    torque_edge = radius_ * k_.linear_edge.kte * te;
  }

  /// max_θ |F(θ; c)| [N] at feed per tooth c [mm].
  double peak(double c) const {
    const double cp = std::pow(c, p), cq = std::pow(c, q);
    double m = 0.0;
    for (Eigen::Index i = 0; i < P.rows(); ++i) m = std::max(m, (cp * P.row(i) + cq * Q.row(i)).norm());
    return m;
  }

  bool ball() const { return ball_; }
  Points3 P, Q;
  double p = 1.0, q = 0.0;
  double torque_cutting = 0.0, torque_edge = 0.0;  // mean T = c·cutting + edge [N·mm]

 private:
  bool ball_;
  double radius_;
  force::ProgramCoefficients k_;
  force::FlatEndModel fm_;
  force::BallEndModel bm_;
  force::LinearEdgeCoefficients cut_, edge_;
  force::BallEndCoefficients tan_, rad_;
  force::FlatEndWorkspace fws_;
  force::BallEndWorkspace bws_;
  force::EngagementMap map_;
};

using Allowed = std::array<double, feed_limit_columns>;

/// The largest feed [mm/s] each limit allows at an engaged sample (FeedLimit 0..5; inf: no bound).
/// Deflection and wall error here for ball end mills only (the cantilever bound of the file comment);
/// flat end mills take them from SampleDeflection.
Allowed allowed_feeds(const SampleForces& sf, const MaskFacts& m, const FeedLimits& lim,
                      const deflection::Cantilever& beam, double holder_compliance, int flutes, double rpm) {
  Allowed al;
  al.fill(inf);
  const double to_feed = flutes * rpm / 60.0;  // [mm/s] per [mm/tooth]
  // g(x; l) ≤ g(L; L) for every x, l in [0, L]: the tip under a load at the tip deflects most, so κ·|F|
  // bounds the deflection anywhere on the tool for any split of F over the engaged height that pushes
  // one way (a load at mid-height, g(L; L − a/2), did not: g is convex in l, and a ball's load sits low).
  const double kappa = beam.influence(beam.length, beam.length) + holder_compliance;
  const Vec3 all(1, 1, 1), xy(1, 1, 0), y(0, 1, 0);
  auto largest = [&](const Vec3& w, double limit) {
    return detail::largest_feed_per_tooth(sf.P, sf.Q, sf.p, sf.q, w, limit) * to_feed;
  };
  al[0] = largest(all, lim.max_force);
  if (m.chip > 0.0) al[1] = lim.max_chip / m.chip * to_feed;
  if (sf.ball()) {
    al[2] = largest(xy, lim.max_deflection / kappa);
    if (m.walls) al[3] = largest(y, lim.max_wall_error / kappa);
  } else {
    auto torque_feed = [&](double t_nmm) {
      if (!std::isfinite(t_nmm)) return inf;
      if (sf.torque_edge >= t_nmm) return 0.0;
      return sf.torque_cutting > 0 ? (t_nmm - sf.torque_edge) / sf.torque_cutting * to_feed : inf;
    };
    al[4] = torque_feed(lim.max_power / (two_pi * rpm / 60.0) * 1e3);
    al[5] = torque_feed(lim.max_torque * 1e3);
  }
  return al;
}

/// Samples gathered along the program, turned into FeedSamples at the end.
struct Collected {
  std::vector<Vec3> pos, dir;
  std::vector<int> block;
  std::vector<double> fraction, rpm, lowest, force, deflection, wall_error;
  std::vector<MaskFacts> facts;
  std::vector<Allowed> allowed;

  void into(FeedSamples& out) const {
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
    out.engaged_share.resize(m);
    out.allowed.resize(m, feed_limit_columns);
    out.lowest.resize(m);
    out.force.resize(m);
    out.deflection.resize(m);
    out.wall_error.resize(m);
    for (Eigen::Index i = 0; i < m; ++i) {
      out.positions.row(i) = pos[i].transpose();
      out.feed_direction.row(i) = dir[i].transpose();
      out.block[i] = block[i];
      out.fraction[i] = fraction[i];
      out.spindle_rpm[i] = rpm[i];
      out.engaged[i] = facts[i].engaged ? 1 : 0;
      out.walls[i] = facts[i].walls;
      out.depth[i] = facts[i].depth;
      out.chip_factor[i] = facts[i].chip;
      out.engaged_share[i] = facts[i].share;
      for (int j = 0; j < feed_limit_columns; ++j) out.allowed(i, j) = allowed[i][j];
      out.lowest[i] = lowest[i];
      out.force[i] = force[i];
      out.deflection[i] = deflection[i];
      out.wall_error[i] = wall_error[i];
    }
  }
};

void check_inputs(const cutter::Cutter& cutter, const force::ProgramCoefficients& k, const FeedLimits& limits,
                  const FeedScheduleOptions& options) {
  options.validate();
  limits.validate();
  cutter.validate();
  NETSHAPE_CHECK(cutter.kind != cutter::CutterKind::bull, "cutter.kind", "bull",
                 "feed scheduling models flat and ball end mills");
  NETSHAPE_CHECK(k.chip.none(), "chip", "runout/size effect",
                 "feed scheduling solves the linear chip's force c·P + Q (docs/feeds.md)");
  if (cutter.kind == cutter::CutterKind::ball) {
    k.ball_end.validate();
    NETSHAPE_CHECK(!std::isfinite(limits.max_power) && !std::isfinite(limits.max_torque), "max_power_W",
                   limits.max_power, "power and torque limits are modelled for flat end mills");
  } else {
    k.linear_edge.validate();
  }
}

}  // namespace

FeedSamples feed_samples(stock::ZMap& stock, const cutter::Cutter& cutter, const toolpath::Toolpath& program,
                         const force::ProgramCoefficients& k, const FeedLimits& limits,
                         const FeedScheduleOptions& options) {
  check_inputs(cutter, k, limits, options);
  const force::ProgramForceOptions& opt = options.sampling;
  VectorXd phi(opt.bins);
  for (int b = 0; b < opt.bins; ++b) phi[b] = (b + 0.5) * two_pi / opt.bins;
  const VectorXd angles = force::rotation_angles(opt.samples_per_revolution);
  const deflection::Cantilever beam = deflection::Cantilever::tool(
      cutter.diameter(), cutter.stick_out, cutter.youngs_modulus, deflection::InertiaModel::square);
  SampleForces sf(cutter, k, opt, angles.size());
  const bool flat_deflection = cutter.kind == cutter::CutterKind::flat &&
                               (std::isfinite(limits.max_deflection) || std::isfinite(limits.max_wall_error));
  std::optional<detail::SampleDeflection> sd;
  if (flat_deflection) sd.emplace(cutter, k.linear_edge, opt.disk_height, angles);
  stock::MaskR mask;
  Collected c;
  FeedSamples out;
  auto visit = [&](const force::WalkSample& w) {
    const toolpath::Block& b = program.blocks[w.block];
    const double rpm = opt.spindle_rpm > 0 ? opt.spindle_rpm : std::abs(b.spindle_rpm);
    double dz = 0.0;
    const VectorXd& z = sf.heights(w.depth, w.tangent, dz);
    stock::engaged_elements_into(stock, cutter, w.tip, w.feed_direction, phi, z, mask);
    const MaskFacts facts = read_mask(mask, phi, z, dz);
    Allowed al;
    al.fill(inf);
    double low = 0.0, fprog = 0.0, defl = 0.0, wall = 0.0;
    if (facts.engaged) {
      NETSHAPE_CHECK(rpm > 0.0, ("block at line " + std::to_string(b.line) + ": spindle_rpm").c_str(), rpm,
                     "a cutting move needs a spindle speed (S word) [rev/min]");
      sf.evaluate(mask, angles);
      al = allowed_feeds(sf, facts, limits, beam, cutter.holder_compliance, cutter.flutes, rpm);
      const double to_feed = cutter.flutes * rpm / 60.0;
      if (facts.chip > 0.0) low = limits.min_chip / facts.chip * to_feed;
      fprog = sf.peak(b.feed / to_feed);
      if (sd) {
        const auto d = sd->evaluate(stock, w.tip, w.feed_direction, facts.walls, b.feed / to_feed,
                                    limits.max_deflection, limits.max_wall_error);
        al[2] = d.deflection_c * to_feed;
        al[3] = d.wall_c * to_feed;
        defl = d.deflection;
        wall = d.wall_error;
      }
    }
    c.pos.push_back(w.tip);
    c.dir.push_back(w.feed_direction);
    c.block.push_back(static_cast<int>(w.block));
    c.fraction.push_back(w.fraction);
    c.rpm.push_back(rpm);
    c.facts.push_back(facts);
    c.allowed.push_back(al);
    c.lowest.push_back(low);
    c.force.push_back(fprog);
    c.deflection.push_back(defl);
    c.wall_error.push_back(wall);
  };
  out.removed_volume = force::walk_program(stock, cutter, program, opt.step, visit, "feeds");
  c.into(out);
  return out;
}

}  // namespace netshape::compensation
