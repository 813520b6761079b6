#include <doctest/doctest.h>

#include <cmath>
#include <limits>
#include <stdexcept>

#include "netshape/stock/zmap.hpp"

using netshape::MatrixXdR;
using netshape::Vec3;
using netshape::stock::ZMap;

TEST_CASE("zmap: grid of cell-centred nodes keeps the footprint exactly") {
  const ZMap z(0.0, 100.0, 0.0, 100.0, 0.1, 10.0, 0.0);
  CHECK(z.nx() == 1000);
  CHECK(z.ny() == 1000);
  CHECK(z.dx() == doctest::Approx(0.1));
  CHECK(z.node_x(0) == doctest::Approx(0.05));
  CHECK(z.node_y(999) == doctest::Approx(99.95));
  CHECK(z.volume() == doctest::Approx(100.0 * 100.0 * 10.0));

  // 10 / 0.3 is not whole: 34 cells of 10/34 ≤ 0.3 mm
  const ZMap w(-5.0, 5.0, 0.0, 1.0, 0.3, 1.0, -1.0);
  CHECK(w.nx() == 34);
  CHECK(w.dx() <= 0.3);
  CHECK(w.dx() * w.nx() == doctest::Approx(10.0));
  CHECK(w.ny() == 4);
}

TEST_CASE("zmap: pillar and bilinear queries") {
  MatrixXdR h(3, 4);
  // plane h = 1 + 0.5 x + 0.25 y at the node centres of [0,4]x[0,3] with unit cells
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 4; ++j) h(i, j) = 1.0 + 0.5 * (j + 0.5) + 0.25 * (i + 0.5);
  const ZMap z = ZMap::from_heights(h, 0.0, 4.0, 0.0, 3.0, -2.0);
  CHECK(z.nx() == 4);
  CHECK(z.ny() == 3);
  // bilinear reproduces a plane between the nodes
  CHECK(z.height_at(1.3, 1.7) == doctest::Approx(1.0 + 0.5 * 1.3 + 0.25 * 1.7));
  CHECK(z.height_at(0.5, 0.5) == doctest::Approx(h(0, 0)));
  // between the outermost node and the edge: the edge row/column is held
  CHECK(z.height_at(0.1, 0.5) == doctest::Approx(h(0, 0)));
  CHECK(std::isnan(z.height_at(-0.1, 1.0)));
  CHECK(std::isnan(z.height_at(std::nan(""), 1.0)));
  // pillars
  CHECK(z.cell_height(1.99, 2.5) == doctest::Approx(h(2, 1)));
  CHECK(z.cell_height(4.0, 3.0) == doctest::Approx(h(2, 3)));  // far edges belong to the last cell
  CHECK(z.is_material(Vec3(1.5, 1.5, h(1, 1) - 1e-9)));
  CHECK_FALSE(z.is_material(Vec3(1.5, 1.5, h(1, 1))));
  CHECK_FALSE(z.is_material(Vec3(1.5, 1.5, -2.5)));  // below the bottom
  CHECK(z.is_material(Vec3(1.5, 1.5, -2.0)));
  CHECK_FALSE(z.is_material(Vec3(5.0, 1.5, 0.0)));   // outside the footprint

  netshape::Points3 p(2, 3);
  p << 1.5, 1.5, 0.0, 9.0, 9.0, 0.0;
  const auto m = z.is_material_points(p);
  CHECK(m[0]);
  CHECK_FALSE(m[1]);
  const auto hb = z.height_at_points(MatrixXdR(p));
  CHECK(hb[0] == doctest::Approx(1.0 + 0.75 + 0.375));
  CHECK(std::isnan(hb[1]));
}

TEST_CASE("zmap: bad input names the field and never allocates a giant grid") {
  CHECK_THROWS_WITH_AS(ZMap(0, 1, 0, 1, 0.0, 1, 0), doctest::Contains("zmap.spacing = 0"), std::invalid_argument);
  CHECK_THROWS_WITH_AS(ZMap(0, 1, 0, 1, -0.1, 1, 0), doctest::Contains("zmap.spacing"), std::invalid_argument);
  CHECK_THROWS_WITH_AS(ZMap(1, 0, 0, 1, 0.1, 1, 0), doctest::Contains("zmap.x1"), std::invalid_argument);
  CHECK_THROWS_WITH_AS(ZMap(0, 1, 0, 1, 0.1, 1, 2), doctest::Contains("zmap.bottom"), std::invalid_argument);
  CHECK_THROWS_WITH_AS(ZMap(0, std::nan(""), 0, 1, 0.1, 1, 0), doctest::Contains("zmap.x1"), std::invalid_argument);
  CHECK_THROWS_WITH_AS(ZMap(0, 1, 0, 1, 0.1, std::numeric_limits<double>::infinity(), 0),
                       doctest::Contains("zmap.top"), std::invalid_argument);
  // 1 m x 1 m at 1 µm would be 1e12 nodes
  CHECK_THROWS_WITH_AS(ZMap(0, 1000, 0, 1000, 1e-3, 1, 0), doctest::Contains("too many grid nodes"),
                       std::invalid_argument);
  CHECK_THROWS_WITH_AS(ZMap(0, 1000, 0, 1000, 1e-300, 1, 0), doctest::Contains("zmap.spacing"),
                       std::invalid_argument);
  MatrixXdR h = MatrixXdR::Constant(2, 2, 1.0);
  h(1, 1) = std::nan("");
  CHECK_THROWS_WITH_AS(ZMap::from_heights(h, 0, 1, 0, 1, 0), doctest::Contains("zmap.heights"), std::invalid_argument);
  h(1, 1) = -1.0;
  CHECK_THROWS_WITH_AS(ZMap::from_heights(h, 0, 1, 0, 1, 0), doctest::Contains("below the bottom"),
                       std::invalid_argument);
  ZMap z(0, 1, 0, 1, 0.5, 1, 0);
  CHECK_THROWS_WITH_AS(z.set_heights(MatrixXdR::Zero(3, 2)), doctest::Contains("zmap.heights.shape"),
                       std::invalid_argument);
}
