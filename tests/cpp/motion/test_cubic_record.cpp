// netshape::motion cubic-record kernels (src/motion/cubic_record.hpp): the copy of the chosen
// instruction set gives the same bits as the baseline one on every piece of a record.
#include <doctest/doctest.h>

#include <algorithm>
#include <cstring>
#include <random>
#include <string>

#include "motion/kernels/cubic_record_kernels.hpp"
#include "netshape/motion.hpp"

using namespace netshape;
using namespace netshape::motion;
using detail::CubicRecord;

namespace {
// the first np entries of two rows hold the same bits
bool same(const double* a, const double* b, int np) { return std::memcmp(a, b, sizeof(double) * static_cast<std::size_t>(np)) == 0; }
}  // namespace

TEST_CASE("cubic-record kernels: the chosen instruction set gives the same bits as the baseline") {
  const auto& best = detail::cubic_record_kernels();
  const auto& plain = detail::cubic_record_kernels_plain();
  MESSAGE("cubic-record kernels in use: " << std::string(best.isa));
  std::mt19937 rng(9);
  std::uniform_real_distribution<double> uni(0.0, 1.0);
  const double A[3] = {3000.0, 2000.0, 1500.0}, V[3] = {250.0, 200.0, 150.0};
  int odd_cases = 0, bad_lanes = 0;
  for (int trial = 0; trial < 400; ++trial) {
    CubicRecord ra;
    ra.np = 1 + static_cast<int>(uni(rng) * CubicRecord::pieces) % CubicRecord::pieces;
    const int dead = static_cast<int>(uni(rng) * 4);  // an axis that does not move (3: none)
    for (int k = 0; k < ra.np; ++k) {
      ra.len[k] = trial % 7 == 0 && k == 0 ? 0.0 : 0.5 * uni(rng);
      ra.vs[k] = 200 * uni(rng);
      ra.ve[k] = 200 * uni(rng);
      for (int i = 0; i < 3; ++i) {
        const bool moves = i != dead;
        ra.u_abs[i][k] = moves ? uni(rng) : 0.0;
        ra.k_abs[i][k] = moves ? 2.0 * uni(rng) : 0.0;
        ra.ramp_u[0][i][k] = ra.ramp_u[1][i][k] = ra.u_abs[i][k] * uni(rng);
        for (int d = 0; d < 2; ++d) ra.ramp_k[d][i][k] = ra.k_abs[i][k] * (2.0 * uni(rng) - 1.0);
      }
    }
    // the same input to both copies
    CubicRecord x = ra, y = ra;
    const double feed = 150 + 100 * uni(rng);
    const unsigned bx = best.caps_reach(x, feed, V, A), by = plain.caps_reach(y, feed, V, A);
    odd_cases += ra.np % 2;
    bad_lanes += __builtin_popcount(bx);
    CHECK(bx == by);
    const int np = ra.np;
    CHECK(same(x.v_max, y.v_max, np));
    for (int i = 0; i < 3; ++i) {
      CHECK(same(x.alpha[i], y.alpha[i], np));
      CHECK(same(x.beta[i], y.beta[i], np));
      CHECK(same(x.alpha_down[i], y.alpha_down[i], np));
      CHECK(same(x.beta_down[i], y.beta_down[i], np));
    }
    // junction limits and the axes that can bind in the backward step, against their definition
    const double v_corner = 300 * uni(rng);
    best.junctions(x, v_corner);
    plain.junctions(y, v_corner);
    CHECK(same(x.w_junction, y.w_junction, np));
    REQUIRE(x.live_down == y.live_down);
    int live = 0;
    for (int i = 0; i < 3; ++i) {
      bool binds = false;
      for (int k = 0; k < np; ++k) {
        const double vj = std::min(k == 0 ? v_corner : x.v_max[k - 1], x.v_max[k]);
        CHECK(x.w_junction[k] == vj * vj);
        binds = binds || !(x.alpha_down[i][k] >= 0.0 && x.beta_down[i][k] >= x.w_junction[k]);
      }
      if (binds) {
        REQUIRE(live < x.live_down);
        CHECK(x.live_down_axis[live] == i);
        CHECK(y.live_down_axis[live] == i);
        ++live;
      }
    }
    CHECK(live == x.live_down);
    best.freeze(x, A, 1500.0);
    plain.freeze(y, A, 1500.0);
    for (const auto row : {&CubicRecord::vp, &CubicRecord::acc, &CubicRecord::t1, &CubicRecord::t2, &CubicRecord::t3,
                           &CubicRecord::d1, &CubicRecord::d2, &CubicRecord::d3, &CubicRecord::dur})
      CHECK(same(x.*row, y.*row, np));
  }
  CHECK(odd_cases > 50);
  CHECK(bad_lanes > 10);  // the pieces left to set_box_reach() are reported alike
}
