// Engagement over separate material regions along a path (path_wall_errors): a sliver of material beside
// an air gap loads the tool with its own force only. Checked against wall_errors of the same model with the
// two windows the stock's closed-form geometry gives.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>

#include "netshape/compensation.hpp"
#include "netshape/cutter.hpp"
#include "netshape/deflection.hpp"
#include "netshape/stock.hpp"

using namespace netshape;
using namespace netshape::compensation;

namespace {
constexpr double R = 3.0, h = 0.05;

cutter::Cutter tool() {
  cutter::Cutter c = cutter::Cutter::flat_end(2 * R, 4, deg2rad(30.0));
  c.flute_length = 10.0;
  c.stick_out = 30.0;
  return c;
}

deflection::DeflectionModel model() {
  deflection::DeflectionModel m;
  m.force.radius = R;
  m.force.flutes = 4;
  m.force.helix = deg2rad(30.0);
  m.force.feed_per_tooth = 0.05;
  m.force.disk_height = 0.05;
  m.force.coefficient_model = force::FlatCoefficientModel::linear_edge;
  m.force.linear_edge = {958.8, 251.1, 146.4, 15.8, 19.4, 18.2};
  m.beam = deflection::Cantilever::tool(2 * R, 30.0, 600e3, deflection::InertiaModel::square);
  return m;
}

// Stock 2 mm high (the tip at z = 0): the wall side y < −1 and a ridge lo ≤ y < hi (multiples of h),
// cleared elsewhere. Node centres lie h/2 either side of each edge, so the bilinear material edges are
// exactly there.
stock::ZMap ridge_stock(double lo, double hi) {
  const double x0 = -10.0, x1 = 20.0, y0 = -6.0, y1 = 6.0;
  const int nx = static_cast<int>(std::lround((x1 - x0) / h));
  const int ny = static_cast<int>(std::lround((y1 - y0) / h));
  MatrixXdR heights(ny, nx);
  for (int i = 0; i < ny; ++i) {
    const double y = y0 + (i + 0.5) * h;
    heights.row(i).setConstant(y < -1.0 || (y >= lo && y < hi) ? 2.0 : -1.0);
  }
  return stock::ZMap::from_heights(heights, x0, x1, y0, y1, -2.0);
}

// n points along +X at y = 0, z = 0 from x = 0 to 10, down milling (right wall, −Y), no offsets
PathWallErrors run(const stock::ZMap& zmap, int n) {
  Points3 path(n, 3);
  Points2 normals(n, 2);
  for (int i = 0; i < n; ++i) {
    path.row(i) << 10.0 * i / (n - 1), 0.0, 0.0;
    normals.row(i) << 0.0, -1.0;
  }
  PathOptions po;
  po.side = deflection::WallSide::right;
  return path_wall_errors(model(), tool(), zmap, path, normals, VectorXd::Zero(n), po);
}
}  // namespace

TEST_CASE("path: a sliver behind an air gap adds its own window's force, not the gap's") {
  // 6 mm flat end mill: material runs at φ ∈ [acos(0.5/R), acos(0.2/R)] (the ridge ahead of the tool, where
  // flutes pass at the wall's generation instants) and [acos(−1/R), π] (the cut, width 2 mm); the ridge and
  // the wall behind the tool are swept by its earlier moves.
  const PathWallErrors r = run(ridge_stock(0.2, 0.5), 41);
  const force::AngularEngagement ridge{std::acos(0.5 / R), std::acos(0.2 / R)};
  const VectorXd z = deflection::cut_levels(2.0);
  for (int i = 10; i <= 30; ++i) {
    CAPTURE(i);
    CHECK(r.engaged[i] == 1);
    CHECK(r.depth[i] == doctest::Approx(2.0));
    CHECK(r.wall_flags[i] == 2);  // the right wall only: φ = 0 lies in the gap before the ridge
    // the reported window runs from the first to the last material angle (the exit a few 1e-5 rad past π,
    // where the last move's sweep starts)
    CHECK(r.phi_st[i] == doctest::Approx(ridge.phi_st).epsilon(1e-6));
    CHECK(r.phi_ex[i] == doctest::Approx(pi).epsilon(1e-4));
    deflection::DeflectionModel two = model(), span = model();
    two.force.axial_depth = span.force.axial_depth = 2.0;
    two.windows = {ridge, {std::acos(-1.0 / R), r.phi_ex[i]}};
    span.force.engagement = {ridge.phi_st, r.phi_ex[i]};
    deflection::DeflectionWorkspace ws(two);
    const deflection::WallErrors expect = deflection::wall_errors(two, ws, deflection::WallSide::right, z);
    const deflection::WallErrors spanning = deflection::wall_errors(span, ws, deflection::WallSide::right, z);
    for (int k = 0; k < 3; ++k) {
      CHECK(r.error(i, k) == doctest::Approx(expect.error[k]).epsilon(1e-6).scale(1e-6));
      CHECK(std::abs(r.error(i, k) - spanning.error[k]) > 0.1 * std::abs(expect.error[k]));
    }
  }
}

TEST_CASE("path: a thinner sliver loads the tool less, down to the cut without it") {
  // ridges 0.2 ≤ y < 0.2 + t: the sliver's run of angles, and with it its share of the error (with minus
  // without the ridge), shrinks with t (1.0° for t = 0.05 mm against 7.7° for 0.3 mm); a window spanning
  // the gap would keep the whole gap's share however thin the sliver.
  const PathWallErrors without = run(ridge_stock(-100.0, -100.0), 41);
  double share[2];
  const double t[2] = {0.3, 0.05};
  for (int c = 0; c < 2; ++c) {
    const PathWallErrors with = run(ridge_stock(0.2, 0.2 + t[c]), 41);
    share[c] = std::abs(with.error(20, 1) - without.error(20, 1));
  }
  CHECK(share[0] > 0.01 * std::abs(without.error(20, 1)));
  CHECK(share[1] < 0.3 * share[0]);
}
