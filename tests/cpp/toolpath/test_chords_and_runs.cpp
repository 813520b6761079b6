// The arc chord count and the collinear-run test: the one function of each fact (toolpath.hpp).
// Oracle: a chord spanning θ on radius r deviates r·(1 − cos(θ/2)) from the arc (sagitta).
#include <doctest/doctest.h>

#include <cmath>

#include "netshape/toolpath/toolpath.hpp"

using namespace netshape;
using namespace netshape::toolpath;

TEST_CASE("chord_count: the fewest chords whose sagitta is within the tolerance") {
  for (double r : {0.5, 3.0, 10.0, 250.0})
    for (double sweep : {0.1, 1.0, pi, 2 * pi, 5 * pi})
      for (double tol : {1e-4, 2e-3, 0.05}) {
        if (tol >= r) continue;
        const int n = chord_count(r, sweep, tol);
        const double sagitta = r * (1.0 - std::cos(0.5 * sweep / n));
        CHECK(sagitta <= tol * (1.0 + 1e-9));
        if (n > 1) CHECK(r * (1.0 - std::cos(0.5 * sweep / (n - 1))) > tol);  // n − 1 would not do
        CHECK(chord_count(r, -sweep, tol) == n);  // the sign of the sweep does not matter
      }
  // radius within the tolerance: a chord spans a quarter turn
  CHECK(chord_count(0.001, 2 * pi, 0.002) == 4);
  CHECK(chord_count(0.0, 2 * pi, 0.002) == 1);
  CHECK_THROWS_WITH_AS(chord_count(10.0, pi, 0.0), doctest::Contains("chord_tolerance"), std::invalid_argument);
}

TEST_CASE("continues_run: ahead of b and on the line a-b") {
  const Vec3 a(0, 0, 0), b(1, 1, 0);
  CHECK(continues_run(a, b, Vec3(2, 2, 0)));
  CHECK(continues_run(a, b, Vec3(2, 2, 1e-10)));
  CHECK_FALSE(continues_run(a, b, Vec3(2, 2, 1e-8)));    // off the line
  CHECK_FALSE(continues_run(a, b, Vec3(0.5, 0.5, 0)));   // going back
  CHECK_FALSE(continues_run(a, a, Vec3(2, 2, 0)));       // no direction yet
  CHECK(continues_run(a, b, Vec3(2, 2, 1e-8), 1e-7));    // the tolerance is the caller's
}
