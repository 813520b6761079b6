#include <doctest/doctest.h>

#include <cmath>
#include <utility>
#include <random>
#include <stdexcept>
#include <string>

#include "netshape/geometry/triangle_mesh.hpp"
#include "netshape/posture.hpp"

using namespace netshape;
using namespace netshape::posture;
using geometry::Faces;
using geometry::TriangleMesh;

namespace {
// Vertical wall x = d, y ∈ [−500, 500], z ∈ [−100, 500], facing −x.
TriangleMesh wall(double d) {
  Points3 v(4, 3);
  v << d, -500, -100, d, 500, -100, d, 500, 500, d, -500, 500;
  Faces f(2, 3);
  f << 0, 1, 2, 0, 2, 3;
  return TriangleMesh(v, f);
}

// Largest x reached by the assembly (ball, flat-ended shank and holder cylinders) with the ball centre at
// x = 0 and unit axis T: the rim of an end disc at height z reaches (z − R)·T_x + r·√(1 − T_x²).
double max_x(const CutterAssembly& a, double tx) {
  const double R = a.ball_radius, s = std::sqrt(std::max(0.0, 1.0 - tx * tx));
  double best = R;
  for (const auto& [z, r] : {std::pair{R, a.shank_radius}, std::pair{a.shank_length, a.shank_radius},
                             std::pair{a.shank_length, a.holder_radius}, std::pair{a.holder_length, a.holder_radius}}) {
    best = std::max(best, (z - R) * tx + r * s);
  }
  return best;
}
double max_x(const CutterAssembly& a, const Vec3& t) { return max_x(a, t.x()); }
}  // namespace

TEST_CASE("MB-spline: joins (P_i + 2P_{i+1} + P_{i+2})/4, C1 at the joins, derivative vs finite differences") {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> U(-10, 10);
  Points3 p(9, 3);
  for (Eigen::Index i = 0; i < p.size(); ++i) p.data()[i] = U(rng);
  const Points3 joins = mb_spline_joins(p);
  REQUIRE(joins.rows() == 7);
  for (int i = 0; i + 4 <= p.rows(); ++i) {
    const Vec3 expect = 0.25 * (p.row(i) + 2.0 * p.row(i + 1) + p.row(i + 2)).transpose();
    CHECK((mb_spline_point(p, i, 0.0) - expect).norm() < 1e-12);
    CHECK((joins.row(i).transpose() - expect).norm() < 1e-12);
    if (i + 5 <= p.rows()) {
      CHECK((mb_spline_point(p, i, 1.0) - mb_spline_point(p, i + 1, 0.0)).norm() < 1e-12);
      CHECK((mb_spline_derivative(p, i, 1.0) - mb_spline_derivative(p, i + 1, 0.0)).norm() < 1e-12);
    }
    for (double u : {0.1, 0.5, 0.9}) {
      const double h = 1e-6;
      const Vec3 fd = (mb_spline_point(p, i, u + h) - mb_spline_point(p, i, u - h)) / (2 * h);
      CHECK((fd - mb_spline_derivative(p, i, u)).norm() < 1e-6);
    }
  }
  // smoothing keeps the end points and moves a straight, evenly spaced row nowhere
  Points3 line(6, 3);
  for (int i = 0; i < 6; ++i) line.row(i) << i, 2.0 * i, -i;
  CHECK((mb_smooth(line, 3) - line).norm() < 1e-12);
  const Points3 sm = mb_smooth(p, 2);
  CHECK((sm.row(0) - p.row(0)).norm() < 1e-12);
  CHECK((sm.row(8) - p.row(8)).norm() < 1e-12);
  CHECK_THROWS_AS(mb_spline_point(p, 6, 0.5), std::invalid_argument);
}

TEST_CASE("Interference gap of the assembly against a flat wall equals the closed form") {
  const CutterAssembly a{2.0, 1.5, 25.0, 6.0, 60.0, {}};
  const double d = 30.0;
  const InterferenceChecker chk(wall(d), a, 0.5, 1e-4);
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> U(-1, 1);
  for (int k = 0; k < 200; ++k) {
    Vec3 t(U(rng), U(rng), 1.0 + U(rng));
    t.normalize();
    const Vec3 tip = Vec3(0, 0, a.ball_radius) - a.ball_radius * t;  // ball centre at (0, 0, R)
    const double expect = d - max_x(a, t);
    CHECK(chk.collides(tip, t) == (expect < 0.5));
    // the mesh distance is unsigned: compare gaps only where the assembly stays in front of the wall
    if (expect >= 0.0) CHECK(std::abs(chk.gap(tip, t) - expect) < 2e-4);
  }
}

TEST_CASE("C-obstacle of a single flat wall against its closed form; MC-space midpoint") {
  // CC at the origin, normal +z, feed +y: left b = n × f = −x, so a wall at x = d is on the right (CA2).
  const CutterAssembly a{2.0, 2.0, 25.0, 6.0, 60.0, {}};
  const double d = 20.0, c = 0.5;
  const InterferenceChecker chk(wall(d), a, c, 1e-5);
  const PostureFrame fr = PostureFrame::make(Vec3::Zero(), Vec3::UnitZ(), Vec3::UnitY());
  CSpaceOptions opt;
  const CSpace cs = compute_cspace(chk, fr, opt);
  // closed form: collides iff T_x > t*, the root of max_x(T_x) = d − c (increasing in T_x ∈ [0, 0.9] here)
  double lo = 0.0, hi = 0.9;
  for (int it = 0; it < 100; ++it) (max_x(a, 0.5 * (lo + hi)) > d - c ? hi : lo) = 0.5 * (lo + hi);
  const double t_star = 0.5 * (lo + hi);
  int ca2 = 0;
  for (const BoundaryPoint& b : cs.boundary) {
    CHECK(b.obstacle == 2);
    const double tx = fr.axis(b.theta, b.phi).x();
    CHECK(std::abs(tx - t_star) <= 0.5 * opt.tolerance + 1e-6);
    ++ca2;
  }
  CHECK(ca2 > 10);
  for (int j = 0; j < cs.count_phi; ++j) {
    for (int k = 0; k < cs.count_theta; ++k) {
      const double tx = fr.axis(cs.theta(k), cs.phi(j)).x();
      if (std::abs(tx - t_star) < 1e-6) continue;
      CHECK((cs.state(j, k) == PostureState::ca2) == (tx > t_star));
    }
  }
  // MC: P_b nearest CA2 boundary point to the normal posture is (asin t*, −π/2); CA1 is empty so P_a is the
  // tilt limit on the left (θ_max, +π/2); M is their midpoint in the polar plane.
  const Vec2 m = cs.mc_posture(Vec2(0, 0));
  CHECK(std::abs(m[0] - 0.5 * (opt.theta_max - std::asin(t_star))) < opt.tolerance);
  CHECK(std::abs(m[1] - 0.5 * pi) < 1e-9);
}

TEST_CASE("An assembly boxed in on both sides cannot reach: the error names the CC point") {
  // two walls 3 mm from the CC point on either side, a 2 mm ball: every posture hits one of them
  Points3 v(8, 3);
  v << 3, -500, -100, 3, 500, -100, 3, 500, 500, 3, -500, 500, -3, -500, -100, -3, 500, -100, -3, 500, 500, -3, -500,
      500;
  Faces f(4, 3);
  f << 0, 1, 2, 0, 2, 3, 4, 5, 6, 4, 6, 7;
  const InterferenceChecker chk(TriangleMesh(v, f), CutterAssembly{2.0, 2.0, 25.0, 6.0, 60.0, {}}, 1.5);
  Points3 cc(3, 3), n(3, 3);
  cc << 0, 0, 0, 0, 1, 0, 0, 2, 0;
  n << 0, 0, 1, 0, 0, 1, 0, 0, 1;
  try {
    plan(chk, cc, n);
    FAIL("expected std::invalid_argument");
  } catch (const std::invalid_argument& e) {
    CHECK(std::string(e.what()).find("CC point 0") != std::string::npos);
  }
  n.row(1) << 0, 0, 0;
  try {
    plan(chk, cc, n);
    FAIL("expected std::invalid_argument");
  } catch (const std::invalid_argument& e) {
    CHECK(std::string(e.what()).find("CC point 1") != std::string::npos);
    CHECK(std::string(e.what()).find("degenerate") != std::string::npos);
  }
}

TEST_CASE("Inverse kinematics round trip on table A/C and head B/C; continuous through the singularity") {
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> U(-1, 1);
  for (MachineKind kind : {MachineKind::table_ac, MachineKind::head_bc}) {
    Kinematics k;
    k.kind = kind;
    k.table_centre = Vec3(10, -20, 100);
    k.pivot_length = 150.0;
    Points3 tips(50, 3), axes(50, 3);
    for (int i = 0; i < 50; ++i) {
      tips.row(i) << 50 * U(rng), 50 * U(rng), 20 * U(rng);
      Vec3 a(U(rng), U(rng), 1.2 + U(rng));
      axes.row(i) = a.normalized().transpose();
    }
    const MatrixXdR j = inverse_kinematics(k, tips, axes);
    Points3 t2, a2;
    forward_kinematics(k, j, t2, a2);
    CHECK((t2 - tips).cwiseAbs().maxCoeff() < 1e-9);
    CHECK((a2 - axes).cwiseAbs().maxCoeff() < 1e-12);
    // a sweep of the axis through the C axis (+z): tilt passes through 0, C does not flip
    Points3 st(41, 3), sa(41, 3);
    for (int i = 0; i <= 40; ++i) {
      const double t = deg2rad(-30.0 + 1.5 * i);
      st.row(i) << i, 0, 0;
      sa.row(i) << std::sin(t) * 0.6, std::sin(t) * 0.8, std::cos(t);
    }
    const MatrixXdR js = inverse_kinematics(k, st, sa);
    for (int i = 1; i <= 40; ++i) {
      CHECK(std::abs(js(i, 4) - js(i - 1, 4)) < 1e-9);
      CHECK(std::abs(js(i, 3) - js(i - 1, 3)) < deg2rad(1.5) + 1e-9);
    }
    Points3 ts, as;
    forward_kinematics(k, js, ts, as);
    CHECK((as - sa).cwiseAbs().maxCoeff() < 1e-12);
    k.tilt_min = deg2rad(-10);
    k.tilt_max = deg2rad(10);
    CHECK_THROWS_AS(inverse_kinematics(k, st, sa), std::invalid_argument);
  }
}
