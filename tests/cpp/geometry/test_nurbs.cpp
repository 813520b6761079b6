#include <doctest/doctest.h>

#include <cmath>
#include <random>
#include <stdexcept>

#include "netshape/core/error.hpp"
#include "netshape/geometry.hpp"

using namespace netshape;
using namespace netshape::geometry;

namespace {
// A random clamped knot vector with `count` control points of degree p, optionally with a repeated knot.
VectorXd random_knots(std::mt19937& rng, int count, int p, bool repeat) {
  std::uniform_real_distribution<double> U(0.05, 0.95);
  const int interior = count - p - 1;
  VectorXd k(count + p + 1);
  std::vector<double> in;
  for (int i = 0; i < interior; ++i) in.push_back(U(rng));
  if (repeat && interior >= 2 && p >= 2) in[1] = in[0];
  std::sort(in.begin(), in.end());
  for (int i = 0; i <= p; ++i) {
    k[i] = 0.0;
    k[count + i] = 1.0;
  }
  for (int i = 0; i < interior; ++i) k[p + 1 + i] = in[i];
  return k;
}

NurbsSurface random_surface(std::mt19937& rng, int p, int q, int nu, int nv) {
  std::uniform_real_distribution<double> X(-1.0, 1.0), W(0.5, 2.0);
  Points3 cp(nu * nv, 3);
  VectorXd w(nu * nv);
  for (int i = 0; i < nu; ++i)
    for (int j = 0; j < nv; ++j) {
      cp.row(i * nv + j) << i + 0.3 * X(rng), j + 0.3 * X(rng), X(rng);
      w[i * nv + j] = W(rng);
    }
  return NurbsSurface(p, q, random_knots(rng, nu, p, true), random_knots(rng, nv, q, false), cp, w);
}
}  // namespace

TEST_CASE("basis functions: partition of unity and derivative sums vanish") {
  std::mt19937 rng(7);
  for (int p = 1; p <= 5; ++p) {
    const VectorXd k = random_knots(rng, p + 6, p, true);
    for (double u : {0.0, 0.13, 0.5, 0.77, 1.0}) {
      const MatrixXdR d = basis_function_derivatives(u, p, k, 2);
      CHECK(d.row(0).sum() == doctest::Approx(1.0).epsilon(1e-14));
      CHECK(std::abs(d.row(1).sum()) < 1e-10);
      CHECK(std::abs(d.row(2).sum()) < 1e-8);
    }
  }
}

TEST_CASE("surface derivatives match central finite differences on random rational surfaces") {
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> P(0.05, 0.95);
  for (int trial = 0; trial < 12; ++trial) {
    const int p = 1 + trial % 4, q = 1 + (trial / 2) % 4;
    const NurbsSurface s = random_surface(rng, p, q, p + 4, q + 3);
    for (int k = 0; k < 5; ++k) {
      const double u = P(rng), v = P(rng), h = 1e-5;
      const MatrixXdR d = s.derivatives(u, v, 3);  // D = 4
      auto row = [&](int a, int b) -> Vec3 { return d.row(a * 4 + b).transpose(); };
      const Vec3 fu = (s.point(u + h, v) - s.point(u - h, v)) / (2 * h);
      const Vec3 fv = (s.point(u, v + h) - s.point(u, v - h)) / (2 * h);
      // Only compare where no knot lies within h (derivatives jump at knots of low continuity).
      bool near_knot = false;
      for (int i = 0; i < s.knots_u().size(); ++i) near_knot |= std::abs(s.knots_u()[i] - u) < 3 * h;
      for (int i = 0; i < s.knots_v().size(); ++i) near_knot |= std::abs(s.knots_v()[i] - v) < 3 * h;
      if (near_knot) continue;
      CHECK((row(1, 0) - fu).norm() < 1e-6 * (1 + fu.norm()));
      CHECK((row(0, 1) - fv).norm() < 1e-6 * (1 + fv.norm()));
      const MatrixXdR dpu = s.derivatives(u + h, v, 2), dmu = s.derivatives(u - h, v, 2);
      const Vec3 fuu = (Vec3(dpu.row(3).transpose()) - Vec3(dmu.row(3).transpose())) / (2 * h);
      const Vec3 fuv = (Vec3(dpu.row(1).transpose()) - Vec3(dmu.row(1).transpose())) / (2 * h);
      CHECK((row(2, 0) - fuu).norm() < 1e-5 * (1 + fuu.norm()));
      CHECK((row(1, 1) - fuv).norm() < 1e-5 * (1 + fuv.norm()));
      const Vec3 fuuv = (Vec3(dpu.row(4).transpose()) - Vec3(dmu.row(4).transpose())) / (2 * h);  // ∂u of S_uv
      CHECK((row(2, 1) - fuuv).norm() < 1e-4 * (1 + fuuv.norm()));
    }
  }
}

TEST_CASE("vectorised scattered and grid evaluation agree with the reference algorithm") {
  std::mt19937 rng(3);
  const NurbsSurface s = random_surface(rng, 3, 2, 7, 6);
  const VectorXd us = VectorXd::LinSpaced(9, 0.0, 1.0), vs = VectorXd::LinSpaced(7, 0.0, 1.0);
  SurfaceWorkspace ws = s.make_workspace();
  Points3 gp(63, 3), gn(63, 3), sp(63, 3), sn(63, 3);
  s.evaluate_grid(us, vs, gp, gn, ws);
  Points2 uv(63, 2);
  for (int i = 0; i < 9; ++i)
    for (int j = 0; j < 7; ++j) uv.row(i * 7 + j) << us[i], vs[j];
  s.evaluate(uv, sp, sn, ws);
  for (int k = 0; k < 63; ++k) {
    const Vec3 ref = s.point(uv(k, 0), uv(k, 1));
    const Vec3 nref = s.normal(uv(k, 0), uv(k, 1));
    CHECK((Vec3(gp.row(k).transpose()) - ref).norm() < 1e-13);
    CHECK((Vec3(sp.row(k).transpose()) - ref).norm() < 1e-13);
    CHECK((Vec3(gn.row(k).transpose()) - nref).norm() < 1e-12);
    CHECK((Vec3(sn.row(k).transpose()) - nref).norm() < 1e-12);
  }
}

TEST_CASE("knot insertion leaves curves and surfaces unchanged") {
  std::mt19937 rng(5);
  const NurbsSurface s = random_surface(rng, 3, 3, 6, 5);
  const NurbsSurface su = s.insert_knot_u(0.37, 2);
  const NurbsSurface sv = s.insert_knot_v(0.61, 1);
  CHECK(su.count_u() == s.count_u() + 2);
  CHECK(sv.count_v() == s.count_v() + 1);
  for (double u : {0.0, 0.2, 0.37, 0.5, 0.9, 1.0})
    for (double v : {0.0, 0.1, 0.61, 0.8, 1.0}) {
      CHECK((su.point(u, v) - s.point(u, v)).norm() < 1e-13);
      CHECK((sv.point(u, v) - s.point(u, v)).norm() < 1e-13);
    }
  const NurbsCurve c = s.iso_curve_v(0.3);
  const NurbsCurve c2 = c.insert_knot(0.5, 3);
  for (double u : {0.0, 0.25, 0.5, 0.75, 1.0}) CHECK((c2.point(u) - c.point(u)).norm() < 1e-13);
  CHECK_THROWS_AS(c2.insert_knot(0.5, 1), std::invalid_argument);  // would exceed the degree
}

TEST_CASE("iso-curves are exact cuts of the surface") {
  std::mt19937 rng(9);
  const NurbsSurface s = random_surface(rng, 2, 3, 5, 6);
  const NurbsCurve cu = s.iso_curve_u(0.42), cv = s.iso_curve_v(0.17);
  for (double t : {0.0, 0.3, 0.66, 1.0}) {
    CHECK((cu.point(t) - s.point(0.42, t)).norm() < 1e-13);
    CHECK((cv.point(t) - s.point(t, 0.17)).norm() < 1e-13);
  }
}

TEST_CASE("closest point: projecting S(u,v) + d n recovers (u,v) and distance d") {
  std::mt19937 rng(21);
  std::uniform_real_distribution<double> P(0.1, 0.9);
  const NurbsSurface s = random_surface(rng, 3, 3, 6, 6);
  int checked = 0;
  for (int k = 0; k < 20; ++k) {
    const double u = P(rng), v = P(rng), d = 0.05;
    const Vec3 q = s.point(u, v) + d * s.normal(u, v);
    const SurfaceProjection r = s.closest_point(q);
    CHECK(r.distance <= d + 1e-9);  // never worse than the known foot point
    if (std::abs(r.distance - d) < 1e-9) {
      ++checked;
      CHECK((r.point - s.point(u, v)).norm() < 1e-7);
    }
  }
  CHECK(checked >= 15);
  const NurbsCurve c = s.iso_curve_u(0.5);
  const Vec3 q = c.point(0.3) + Vec3(0, 0, 0.0);
  const CurveProjection cr = c.closest_point(q);
  CHECK(cr.distance < 1e-9);
  CHECK(cr.u == doctest::Approx(0.3).epsilon(1e-8));
}

TEST_CASE("bad input is refused with the field named") {
  Points3 cp(4, 3);
  cp.setRandom();
  VectorXd k(8);
  k << 0, 0, 0, 0, 1, 1, 1, 1;
  CHECK_NOTHROW(NurbsCurve(3, k, cp));
  VectorXd bad = k;
  bad[4] = 0.5;
  bad[5] = 0.2;
  CHECK_THROWS_WITH_AS(NurbsCurve(3, bad, cp), doctest::Contains("non-decreasing"), std::invalid_argument);
  VectorXd w = VectorXd::Ones(4);
  w[2] = -1;
  CHECK_THROWS_WITH_AS(NurbsCurve(3, k, cp, w), doctest::Contains("weights[2]"), std::invalid_argument);
  CHECK_THROWS_AS(NurbsCurve(3, VectorXd::Zero(8), cp), std::invalid_argument);  // empty domain
  CHECK_THROWS_AS(NurbsCurve(2, k, cp), std::invalid_argument);                  // size mismatch
  Points3 nan = cp;
  nan(1, 1) = std::nan("");
  CHECK_THROWS_WITH_AS(NurbsCurve(3, k, nan), doctest::Contains("control_points[1]"), std::invalid_argument);
  const NurbsCurve c(3, k, cp);
  CHECK_THROWS_AS(c.point(1.5), std::invalid_argument);
  CHECK_THROWS_AS(c.point(std::nan("")), std::invalid_argument);
  // coincident control points: fine (the curve is just degenerate there)
  Points3 same = Points3::Zero(4, 3);
  const NurbsCurve z(3, k, same);
  CHECK(z.point(0.5).norm() == 0.0);
  CHECK_THROWS_AS(z.tangent(0.5), netshape::Error);
}

TEST_CASE("basis_functions_d1 equals the general derivative algorithm") {
  std::mt19937 rng(17);
  std::uniform_real_distribution<double> P(0.0, 1.0);
  for (int p = 1; p <= 6; ++p) {
    const VectorXd k = random_knots(rng, p + 5, p, true);
    const int count = p + 5;
    std::vector<double> N(p + 1), dN(p + 1), scratch(ders_scratch_size(p)), ref(2 * (p + 1));
    for (int t = 0; t < 20; ++t) {
      const double u = P(rng);
      const int span = find_span(count, p, u, k.data());
      basis_functions_d1(span, u, p, k.data(), N.data(), dN.data(), scratch.data());
      basis_function_derivatives(span, u, p, 1, k.data(), ref.data(), scratch.data());
      for (int j = 0; j <= p; ++j) {
        CHECK(N[j] == doctest::Approx(ref[j]).epsilon(1e-13));
        CHECK(dN[j] == doctest::Approx(ref[p + 1 + j]).epsilon(1e-12).scale(1.0));
      }
    }
  }
}
