// Flat end mill forces with runout and the chip-size effect (runout_size_effect.hpp) against an
// independent direct element sum of docs/conventions.md §2 (chip h_j = c·sin φ + r_j − r_{j+1} clamped
// at 0, cutting term h_ref·(h/h_ref)^p), and the clamp/holder compliance of the deflection model.
#include <doctest/doctest.h>

#include <cmath>
#include <stdexcept>

#include "netshape/compensation.hpp"
#include "netshape/deflection.hpp"
#include "netshape/force.hpp"
#include "netshape/stock.hpp"
#include "netshape/toolpath.hpp"

#include "flute_order.hpp"

using namespace netshape;
using namespace netshape::force;

namespace {
FlatEndModel cut() {
  FlatEndModel m;
  m.radius = 5.0;
  m.flutes = 3;
  m.helix = deg2rad(30.0);
  m.axial_depth = 3.0;
  m.feed_per_tooth = 0.08;
  m.disk_height = 0.05;
  m.engagement = AngularEngagement::from_mode(MillingMode::down, 5.0, 4.0);
  m.linear_edge = {900.0, 270.0, 150.0, 16.0, 20.0, 10.0};
  return m;
}

// Direct sum over disks and flutes; power law exact (the kernel uses its piecewise-linear interpolant).
Vec3 oracle(const FlatEndModel& m, const RunoutSizeEffect& e, double theta) {
  const int N = m.flutes, disks = m.disks();
  const double dz = m.axial_depth / disks, c = m.feed_per_tooth;
  const double href = e.reference_chip > 0 ? e.reference_chip : c;
  const auto& k = m.linear_edge;
  Vec3 F = Vec3::Zero();
  for (int i = 0; i < disks; ++i) {
    const double z = (i + 0.5) * dz;
    for (int j = 0; j < N; ++j) {
      const double rj = e.runout_rho * std::cos(e.runout_lambda - 2 * pi * j / N);
      const double rp = e.runout_rho * std::cos(e.runout_lambda - 2 * pi * flute_before(j, N) / N);
      double phi = std::fmod(theta + 2 * pi * j / N - m.k_beta() * z, 2 * pi);
      if (phi < 0) phi += 2 * pi;
      if (phi < m.engagement.phi_st || phi > m.engagement.phi_ex) continue;
      const double h = c * std::sin(phi) + rj - rp;
      if (h <= 0) continue;
      const double g = href * std::pow(h / href, e.chip_exponent);
      const double ft = (k.ktc * g + k.kte) * dz, fr = (k.krc * g + k.kre) * dz, fa = (k.kac * g + k.kae) * dz;
      F += Vec3(-ft * std::cos(phi) - fr * std::sin(phi), ft * std::sin(phi) - fr * std::cos(phi), fa);
    }
  }
  return F;
}
}  // namespace

TEST_CASE("no extension is the plain flat end model") {
  const FlatEndModel m = cut();
  const VectorXd th = rotation_angles(90);
  const Points3 a = flat_end_forces(m, th), b = flat_end_forces_extended(m, RunoutSizeEffect{}, th);
  CHECK((a - b).cwiseAbs().maxCoeff() == 0.0);
}

TEST_CASE("runout and size effect match a direct element sum") {
  const FlatEndModel m = cut();
  const VectorXd th = rotation_angles(120);
  for (const RunoutSizeEffect e : {RunoutSizeEffect{0.01, deg2rad(40.0), 1.0, 0.0},
                                   RunoutSizeEffect{0.0, 0.0, 0.7, 0.05},
                                   RunoutSizeEffect{0.006, deg2rad(200.0), 0.8, 0.0}}) {
    const Points3 F = flat_end_forces_extended(m, e, th);
    double worst = 0.0, peak = 0.0;
    for (Eigen::Index a = 0; a < th.size(); ++a) {
      const Vec3 ref = oracle(m, e, th[a]);
      worst = std::max(worst, (F.row(a).transpose() - ref).norm());
      peak = std::max(peak, ref.norm());
    }
    // exact for runout alone; the size effect's interpolant between knots is within 2 % of the peak
    CHECK(worst <= (e.chip_exponent == 1.0 ? 1e-9 : 0.02) * peak);
  }
}

TEST_CASE("runout and size effect: bad input names the field") {
  const FlatEndModel m = cut();
  const VectorXd th = rotation_angles(8);
  CHECK_THROWS_AS(flat_end_forces_extended(m, RunoutSizeEffect{-0.1, 0, 1, 0}, th), std::invalid_argument);
  CHECK_THROWS_AS(flat_end_forces_extended(m, RunoutSizeEffect{0, 0, 2.5, 0}, th), std::invalid_argument);
  CHECK_THROWS_AS(flat_end_forces_extended(m, RunoutSizeEffect{0, 0, 0.8, NAN}, th), std::invalid_argument);
}

TEST_CASE("holder compliance translates the tool by c·F at every height") {
  deflection::DeflectionModel d;
  d.force = cut();
  d.beam = deflection::Cantilever::tool(10.0, 40.0, 600e3, deflection::InertiaModel::square);
  for (auto load : {deflection::LoadModel::resultant, deflection::LoadModel::distributed}) {
    d.load = load;
    deflection::DeflectionWorkspace ws(d);
    deflection::DeflectionModel h = d;
    h.holder_compliance = 2e-4;  // [mm/N]
    for (double z : {0.0, 1.5, 3.0}) {
      disk_forces(d, ws, 0.7);
      const Vec2 a = deflection_from_forces(d, ws, z), b = deflection_from_forces(h, ws, z);
      const Vec2 F(ws.forces().col(0).sum(), ws.forces().col(1).sum());
      CHECK((b - a - 2e-4 * F).norm() <= 1e-12 * (1.0 + a.norm()));
    }
  }
  deflection::DeflectionModel bad = d;
  bad.holder_compliance = -1.0;
  CHECK_THROWS_AS(bad.validate(), std::invalid_argument);
}

TEST_CASE("the deflection model's disk forces carry the same runout and size effect") {
  deflection::DeflectionModel d;
  d.force = cut();
  d.beam = deflection::Cantilever::tool(10.0, 40.0, 600e3, deflection::InertiaModel::square);
  d.smooth_edges = false;  // elements in or out by their centre, as the force kernel
  for (const RunoutSizeEffect e : {RunoutSizeEffect{0.01, deg2rad(40.0), 1.0, 0.0},
                                   RunoutSizeEffect{0.006, deg2rad(200.0), 0.8, 0.05}}) {
    d.chip = e;
    deflection::DeflectionWorkspace ws(d);
    const VectorXd th = rotation_angles(60);
    const Points3 F = flat_end_forces_extended(d.force, e, th);
    double worst = 0.0, peak = 0.0;
    for (Eigen::Index a = 0; a < th.size(); ++a) {
      disk_forces(d, ws, th[a]);
      const Vec2 s(ws.forces().col(0).sum(), ws.forces().col(1).sum());
      worst = std::max(worst, (s - F.row(a).head<2>().transpose()).norm());
      peak = std::max(peak, s.norm());
    }
    // the disk loop evaluates the power law exactly, the force kernel its interpolant (2 %)
    CHECK(worst <= (e.chip_exponent == 1.0 ? 1e-9 : 0.02) * peak);
  }
}

TEST_CASE("with an engagement map: the window model's chip on the elements the map marks") {
  FlatEndModel m = cut();
  const VectorXd th = rotation_angles(120);
  // a slot: the bins of [0, π] are exactly the window's elements, so both models sum the same terms
  m.engagement = AngularEngagement::from_mode(MillingMode::slot, 5.0, 10.0);
  const EngagementMap slot = EngagementMap::from_window(m.engagement, m.disks(), 360);
  FlatEndWorkspace ws(m);
  Points3 G(th.size(), 3);
  for (const RunoutSizeEffect e : {RunoutSizeEffect{0.01, deg2rad(40.0), 1.0, 0.0},
                                   RunoutSizeEffect{0.006, deg2rad(200.0), 0.7, 0.05}}) {
    const Points3 F = flat_end_forces_extended(m, e, th);
    flat_end_forces_extended(m, e, ws, th, G, slot);
    CHECK((F - G).cwiseAbs().maxCoeff() <= 1e-9 * F.cwiseAbs().maxCoeff());
    // runout loads the flutes unequally: the force is no longer periodic over a flute pitch
    const Eigen::Index pitch = th.size() / m.flutes;
    double shift = 0.0;
    for (Eigen::Index a = 0; a + pitch < th.size(); ++a)
      shift = std::max(shift, (G.row(a) - G.row(a + pitch)).norm());
    CHECK(shift > 0.05 * G.rowwise().norm().maxCoeff());
  }
  // a down-milling window: the map differs only in the bins cut by the window's edges
  m.engagement = AngularEngagement::from_mode(MillingMode::down, 5.0, 4.0);
  const EngagementMap down = EngagementMap::from_window(m.engagement, m.disks(), 3600);
  const RunoutSizeEffect e{0.008, deg2rad(90.0), 0.8, 0.0};
  const Points3 F = flat_end_forces_extended(m, e, th);
  flat_end_forces_extended(m, e, ws, th, G, down);
  CHECK((F - G).rowwise().norm().maxCoeff() <= 0.02 * F.rowwise().norm().maxCoeff());
  // nothing set: exactly the plain kernel with the map
  Points3 P(th.size(), 3);
  flat_end_forces(m, ws, th, P, &down);
  flat_end_forces_extended(m, RunoutSizeEffect{}, ws, th, G, down);
  CHECK((P - G).cwiseAbs().maxCoeff() == 0.0);
}

TEST_CASE("the program force simulation carries the chip; the feed schedule refuses it") {
  const toolpath::Toolpath prog = toolpath::parse_gcode("G21 G90 G0 X-6 Y0 Z0\nS6000 M3\nG1 X12 F900\n");
  ProgramCoefficients k;
  k.linear_edge = {958.8, 251.1, 146.4, 15.8, 19.4, 18.2};
  ProgramForceOptions opt;
  opt.step = 2.0;
  opt.samples_per_revolution = 36;
  const cutter::Cutter flat = cutter::Cutter::flat_end(8.0, 3, deg2rad(30.0));
  auto run = [&](const cutter::Cutter& c, const ProgramCoefficients& kk) {
    stock::ZMap z(0.0, 12.0, -8.0, 8.0, 0.2, 2.0, -5.0);
    return simulate_program(z, c, prog, kk, opt);
  };
  const ProgramForces plain = run(flat, k);
  ProgramCoefficients kr = k;
  kr.chip = RunoutSizeEffect{0.015, deg2rad(20.0), 1.0, 0.0};
  const ProgramForces with = run(flat, kr);
  REQUIRE(plain.peak_resultant.size() == with.peak_resultant.size());
  CHECK(with.peak_resultant.maxCoeff() > 1.1 * plain.peak_resultant.maxCoeff());  // 1.16
  stock::ZMap z(0.0, 12.0, -8.0, 8.0, 0.2, 2.0, -5.0);
  compensation::FeedLimits lim;
  lim.max_feed = 200.0;
  compensation::FeedScheduleOptions fo;
  fo.sampling = opt;
  CHECK_THROWS_AS(compensation::feed_samples(z, flat, prog, kr, lim, fo), std::invalid_argument);
}

TEST_CASE("runout: flute j cuts the surface flute j + 1 left (arrival order of docs/conventions.md)") {
  CHECK(flute_before(0, 3) == 1);
  CHECK(flute_before(2, 3) == 0);
  CHECK(flute_before(1, 4) == 2);
  CHECK(flute_before(0, 2) == 1);
  // a 3-flute up-milling cut 60° wide: one flute cuts at a time, and the flutes' peaks rank as their own
  // steps r_j − r_{j+1} (with the pairing j − 1 the ranking differs at this λ)
  FlatEndModel m;
  m.radius = 4.0;
  m.flutes = 3;
  m.helix = 0.0;
  m.axial_depth = 1.0;
  m.feed_per_tooth = 0.05;
  m.engagement = AngularEngagement::from_mode(MillingMode::up, 4.0, 2.0);
  m.coefficient_model = FlatCoefficientModel::linear_edge;
  m.linear_edge = {2000.0, 800.0, 300.0, 30.0, 20.0, 5.0};
  RunoutSizeEffect e;
  e.runout_rho = 0.01;
  e.runout_lambda = 0.4;
  const double two_pi = 2.0 * std::acos(-1.0);
  const int n = 720;
  Eigen::VectorXd a(n);
  for (int i = 0; i < n; ++i) a[i] = two_pi * i / n;
  const Points3 F = flat_end_forces_extended(m, e, a);
  double peak[3] = {0, 0, 0};
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < 3; ++j) {
      const double phi = std::fmod(a[i] + j * two_pi / 3, two_pi);
      if (phi < two_pi / 6 + 1e-9) peak[j] = std::max(peak[j], F.row(i).norm());
    }
  auto r = [&](int q) { return e.runout_rho * std::cos(e.runout_lambda - q * two_pi / 3); };
  double step[3];
  for (int j = 0; j < 3; ++j) step[j] = r(j) - r(flute_before(j, 3));
  for (int j = 0; j < 3; ++j)
    for (int q = 0; q < 3; ++q)
      if (step[j] > step[q] + 1e-3) CHECK(peak[j] > peak[q] * 1.05);
}
