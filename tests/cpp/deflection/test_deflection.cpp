// Tool deflection: beam formulas against textbook closed forms and an independent double integration,
// the paper's helix-lag check, and the load models against each other and the force model.
#include <doctest/doctest.h>

#include <cmath>
#include <stdexcept>

#include "netshape/compensation/deflection_compensation.hpp"
#include "netshape/deflection.hpp"
#include "netshape/force.hpp"

using namespace netshape;
using namespace netshape::deflection;

namespace {
// Deflection at x of a unit load at a by integrating the curvature M(s)/EI twice (trapezoid, fine grid):
// an independent check of the closed forms (Euler–Bernoulli, clamped at s = 0).
double integrate_beam(double EI, double a, double x, int steps = 20000) {
  const double h = x / steps;
  double slope = 0.0, defl = 0.0;
  auto curv = [&](double s) { return (s < a ? (a - s) : 0.0) / EI; };
  for (int k = 0; k < steps; ++k) {
    const double s0 = k * h, s1 = s0 + h;
    const double slope1 = slope + 0.5 * h * (curv(s0) + curv(s1));
    defl += 0.5 * h * (slope + slope1);
    slope = slope1;
  }
  return defl;
}

DeflectionModel paper_model() {
  // Cho & Suh 1993 §5: HSS, D = 25 mm, 4 flutes, 60° helix, length 250 mm, f = 0.0127 mm, A = 2.5 mm
  DeflectionModel m;
  m.force.radius = 12.5;
  m.force.flutes = 4;
  m.force.helix = deg2rad(60.0);
  m.force.axial_depth = 2.5;
  m.force.feed_per_tooth = 0.0127;
  m.force.disk_height = 0.05;
  m.force.coefficient_model = force::FlatCoefficientModel::kline_devor;
  m.force.kline_devor = {1000.0, 0.4};
  m.force.engagement = force::AngularEngagement::from_mode(force::MillingMode::down, 12.5, 2.0);
  m.beam = Cantilever::tool(25.0, 250.0, 210e3, InertiaModel::square);
  return m;
}
}  // namespace

TEST_CASE("cantilever: tip deflection P L^3 / 3EI and the point-load formula (Gere & Goodno, Mechanics of Materials)") {
  const Cantilever c{60.0, 210e3, 1000.0};
  const double EI = c.rigidity(), L = c.length;
  CHECK(c.influence(L, L) == doctest::Approx(L * L * L / (3 * EI)).epsilon(1e-14));
  const double a = 45.0;
  // load at a: deflection at the tip a^2 (3L − a) / 6EI, at a itself a^3 / 3EI, at x < a: x^2 (3a − x) / 6EI
  CHECK(c.influence(L, a) == doctest::Approx(a * a * (3 * L - a) / (6 * EI)).epsilon(1e-14));
  CHECK(c.influence(a, a) == doctest::Approx(a * a * a / (3 * EI)).epsilon(1e-14));
  CHECK(c.influence(20.0, a) == doctest::Approx(400.0 * (3 * a - 20.0) / (6 * EI)).epsilon(1e-14));
  // eq. 6 with the Macaulay bracket, both branches
  auto eq6 = [&](double x, double l) {
    const double mac = x > l ? std::pow(x - l, 3) : 0.0;
    return (mac - x * x * x + 3 * x * x * l) / (6 * EI);
  };
  for (double x : {5.0, 30.0, 45.0, 52.0, 60.0}) {
    CHECK(c.influence(x, a) == doctest::Approx(eq6(x, a)).epsilon(1e-12));
    CHECK(c.influence(x, a) == doctest::Approx(integrate_beam(EI, a, x)).epsilon(1e-6));
    CHECK(c.influence(x, a) == doctest::Approx(c.influence(a, x)).epsilon(1e-14));  // Maxwell reciprocity
  }
}

TEST_CASE("cantilever: no unit load anywhere deflects any point more than a tip load deflects the tip") {
  // the bound the ball-end feed schedule takes for its deflection and wall-error limits
  // (compensation/feed_samples.cpp: κ = g(L; L)); a load at mid-height of the cut is not such a bound
  const Cantilever c{45.0, 600e3, 80.0};
  const double L = c.length, top = c.influence(L, L);
  double largest = 0.0;
  for (int i = 0; i <= 90; ++i)
    for (int j = 0; j <= 90; ++j) largest = std::max(largest, c.influence(L * i / 90.0, L * j / 90.0));
  CHECK(largest <= top);
  CHECK(largest == doctest::Approx(top).epsilon(1e-14));
  // a load concentrated 0.5 mm above the tip of a 10 mm deep cut deflects the tip more than the
  // mid-height estimate says: the old κ = g(L; L − a/2) was exceeded
  CHECK(c.influence(L, L - 0.5) > 1.15 * c.influence(L, L - 5.0));  // 1.18 at L = 45 mm
}

TEST_CASE("second moment: inscribed square D^4/48 and equivalent diameter 0.8 D") {
  CHECK(second_moment(10.0, InertiaModel::square) == doctest::Approx(1e4 / 48.0));
  CHECK(second_moment(10.0, InertiaModel::equivalent) == doctest::Approx(pi * std::pow(8.0, 4) / 64.0));
  CHECK_THROWS_AS(second_moment(0.0, InertiaModel::square), std::invalid_argument);
}

TEST_CASE("helix lag of Cho & Suh 1993 §5: 9.92 deg at z = 1.25 mm (D 25, 60 deg)") {
  const DeflectionModel m = paper_model();
  const double lag = generation_angle(m, WallSide::right, 1.25) - generation_angle(m, WallSide::right, 0.0);
  CHECK(rad2deg(lag) == doctest::Approx(9.924).epsilon(1e-3));
  CHECK(std::abs(rad2deg(lag) - 9.915) < 0.01);  // the paper prints 9.915
}

TEST_CASE("distributed load with a single element equals the resultant model") {
  DeflectionModel m = paper_model();
  m.force.disk_height = m.force.axial_depth;  // one disk, its centre at A/2: l = L − A/2
  m.force.engagement = force::AngularEngagement::from_mode(force::MillingMode::slot, 12.5, 25.0);
  DeflectionModel r = m;
  m.load = LoadModel::distributed;
  r.load = LoadModel::resultant;
  DeflectionWorkspace wm(m), wr(r);
  const VectorXd z = (VectorXd(4) << 0.0, 0.7, 1.25, 2.5).finished();
  const WallErrors a = wall_errors(m, wm, WallSide::right, z), b = wall_errors(r, wr, WallSide::right, z);
  for (int k = 0; k < 4; ++k) {
    CHECK(a.error[k] == doctest::Approx(b.error[k]).epsilon(1e-13));
    CHECK(std::abs(a.error[k]) > 1e-4);
  }
}

TEST_CASE("disk forces sum to the force model's total (centre engagement)") {
  for (auto cm : {force::FlatCoefficientModel::kline_devor, force::FlatCoefficientModel::linear_edge}) {
    DeflectionModel m = paper_model();
    m.force.coefficient_model = cm;
    m.force.linear_edge = {958.8, 251.1, 146.4, 15.8, 19.4, 18.2};
    m.smooth_edges = false;
    DeflectionWorkspace ws(m);
    const VectorXd th = force::rotation_angles(97);
    const Points3 f = force::flat_end_forces(m.force, th);
    for (int k = 0; k < th.size(); ++k) {
      disk_forces(m, ws, th[k]);
      CHECK(ws.forces().col(0).sum() == doctest::Approx(f(k, 0)).epsilon(1e-9).scale(1.0));
      CHECK(ws.forces().col(1).sum() == doctest::Approx(f(k, 1)).epsilon(1e-9).scale(1.0));
    }
  }
}

TEST_CASE("smooth edges: the total force over a revolution keeps its mean and changes continuously") {
  DeflectionModel m = paper_model();
  DeflectionModel b = m;
  b.smooth_edges = false;
  DeflectionWorkspace wm(m), wb(b);
  double sm = 0, sb = 0;
  const int n = 3600;
  for (int k = 0; k < n; ++k) {
    const double th = 2 * pi * k / n;
    disk_forces(m, wm, th);
    disk_forces(b, wb, th);
    sm += wm.forces().col(1).sum();
    sb += wb.forces().col(1).sum();
  }
  CHECK(sm / n == doctest::Approx(sb / n).epsilon(2e-3));
  // the wall error changes by less than 1e-3 of itself for a 1e-6 mm change of width
  const VectorXd z = (VectorXd(1) << 1.25).finished();
  m.force.engagement = force::AngularEngagement::from_mode(force::MillingMode::down, 12.5, 2.0);
  const double e0 = wall_errors(m, wm, WallSide::right, z).error[0];
  m.force.engagement = force::AngularEngagement::from_mode(force::MillingMode::down, 12.5, 2.0 + 1e-6);
  const double e1 = wall_errors(m, wm, WallSide::right, z).error[0];
  CHECK(std::abs(e1 - e0) < 1e-3 * std::abs(e0));
}

TEST_CASE("separate windows: a sliver beside an air gap adds its own force, not the gap's") {
  // the main cut [120°, 180°] and a sliver [10°, 16°] behind an air gap, with and without smooth edges
  for (bool smooth : {true, false}) {
    DeflectionModel main = paper_model();
    main.smooth_edges = smooth;
    main.force.engagement = {deg2rad(120.0), pi};
    DeflectionModel sliver = main, both = main, span = main;
    sliver.force.engagement = {deg2rad(10.0), deg2rad(16.0)};
    both.windows = {sliver.force.engagement, main.force.engagement};
    span.force.engagement = {deg2rad(10.0), pi};
    DeflectionWorkspace ws(main);
    const VectorXd z = cut_levels(2.5);
    const WallErrors em = wall_errors(main, ws, WallSide::right, z);
    const WallErrors es = wall_errors(sliver, ws, WallSide::right, z);
    const WallErrors eb = wall_errors(both, ws, WallSide::right, z);
    const WallErrors ew = wall_errors(span, ws, WallSide::right, z);
    for (int k = 0; k < 3; ++k) {
      CHECK(eb.error[k] == doctest::Approx(em.error[k] + es.error[k]).epsilon(1e-12).scale(1e-9));
      for (int c = 0; c < 2; ++c) {
        CHECK(eb.force(k, c) == doctest::Approx(em.force(k, c) + es.force(k, c)).epsilon(1e-12).scale(1e-6));
        CHECK(eb.deflection(k, c) ==
              doctest::Approx(em.deflection(k, c) + es.deflection(k, c)).epsilon(1e-12).scale(1e-9));
      }
      // the window spanning the gap puts force where there is no material
      CHECK(std::abs(ew.error[k] - eb.error[k]) > 0.1 * std::abs(eb.error[k]));
    }
    // one window listed equals the window alone
    DeflectionModel one = main;
    one.windows = {main.force.engagement};
    const WallErrors eo = wall_errors(one, ws, WallSide::right, z);
    for (int k = 0; k < 3; ++k) CHECK(eo.error[k] == em.error[k]);
  }
}

TEST_CASE("wall error sign: down milling leaves material on the right wall, up milling on the left") {
  DeflectionModel m = paper_model();
  DeflectionWorkspace ws(m);
  const VectorXd z = cut_levels(2.5);
  const WallErrors d = wall_errors(m, ws, WallSide::right, z);
  // the force on the cutter pushes it away from the material (+Y_c in down milling)
  CHECK(d.force(1, 1) > 0.0);
  CHECK(d.error[1] > 0.0);
  CHECK(d.error[0] > d.error[2]);  // the tip bends most: the bottom is left thickest
  m.force.engagement = force::AngularEngagement::from_mode(force::MillingMode::up, 12.5, 2.0);
  const WallErrors u = wall_errors(m, ws, WallSide::left, z);
  CHECK(u.error[1] * u.deflection(1, 1) < 0.0);  // e = −δy for the left wall
}

TEST_CASE("bad input: stick-out shorter than the cut, zero E") {
  DeflectionModel m = paper_model();
  m.beam.length = 2.0;
  CHECK_THROWS_AS(m.validate(), std::invalid_argument);
  CHECK_THROWS_AS(Cantilever::tool(25.0, 250.0, 0.0, InertiaModel::square), std::invalid_argument);
  CHECK_THROWS_AS(load_model_from_string("spread"), std::invalid_argument);
}

TEST_CASE("1-D compensation (paper eq. 8): the root leaves no error on the steady cut of width W + C") {
  DeflectionModel m = paper_model();
  const double W = 11.0, z = 1.25;
  const double C = compensation::one_d_compensation(m, WallSide::right, W, z, 1e-9);
  m.force.engagement = force::AngularEngagement::from_mode(force::MillingMode::down, 12.5, W + C);
  DeflectionWorkspace ws(m);
  const VectorXd zl = (VectorXd(1) << z).finished();
  const double e = wall_errors(m, ws, WallSide::right, zl).error[0];
  CHECK(C > 1e-3);                              // the uncompensated error is tens of µm
  CHECK(std::abs(e - C) < 1e-8);                // D[W + C] = C
}
