// netshape::motion line-blend kernels (src/motion/line_blend.hpp): the copy of the chosen instruction
// set gives the same bits as the baseline one, and the kernels agree with an independent evaluation of the blend.
#include <doctest/doctest.h>

#include <cmath>
#include <cstring>
#include <random>
#include <string>

#include "motion/kernels/line_blend_kernels.hpp"
#include "netshape/motion.hpp"

using namespace netshape;
using namespace netshape::motion;

namespace {
Vec3 random_unit(std::mt19937& rng) {
  std::normal_distribution<double> g;
  Vec3 v(g(rng), g(rng), g(rng));
  return v / v.norm();
}
}  // namespace

TEST_CASE("line-blend kernels: the chosen instruction set gives the same bits as the baseline") {
  const auto& best = detail::line_blend_kernels();
  const auto& plain = detail::line_blend_kernels_plain();
  MESSAGE("line-blend kernels in use: " << std::string(best.isa));
  const auto& T = detail::line_blend_tables();
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> uni(0.0, 1.0);
  int multi = 0, single = 0;
  for (int trial = 0; trial < 400; ++trial) {
    const Vec3 u1 = random_unit(rng);
    // every kind of turn: near-straight, right-angle, near-reversal
    Vec3 u2 = random_unit(rng);
    if (trial % 4 == 0) u2 = (u1 + 0.02 * uni(rng) * random_unit(rng)).normalized();
    const double d = 1e-3 + 2.0 * uni(rng);
    const Vec3 vtx(100 * uni(rng), 100 * uni(rng), 100 * uni(rng));
    const Vec3 A(1000 + 4000 * uni(rng), 1000 + 4000 * uni(rng), 500 + 2000 * uni(rng));
    const Vec3 V(100 + 200 * uni(rng), 100 + 200 * uni(rng), 50 + 100 * uni(rng));
    const double vfeed = 20 + 400 * uni(rng), v_prev = 300 * uni(rng);
    Segment sa, sb;
    detail::LineBlendRecord ra, rb;
    const int na = best.build(T, sa, vtx - d * u1, vtx, vtx + d * u2, u1, u2, d, trial, A, V, A.cwiseInverse(),
                              vfeed, v_prev, ra);
    const int nb = plain.build(T, sb, vtx - d * u1, vtx, vtx + d * u2, u1, u2, d, trial, A, V, A.cwiseInverse(),
                               vfeed, v_prev, rb);
    REQUIRE(na == nb);
    (na > 1 ? multi : single) += 1;
    CHECK(std::memcmp(sa.table.data(), sb.table.data(), sizeof(sa.table)) == 0);
    CHECK(std::memcmp(&sa.curvature, &sb.curvature, sizeof(double)) == 0);
    CHECK(std::memcmp(&sa.curvature_rate, &sb.curvature_rate, sizeof(double)) == 0);
    CHECK(std::memcmp(&ra, &rb, sizeof(ra)) == 0);
    // freeze from some start speed into some allowed end speed
    const double vs = std::sqrt(ra.w_junction[0]) * uni(rng), wt = ra.w_junction[na - 1] * uni(rng);
    const double ea = best.freeze(ra, vs, wt, A, 1.5), eb = plain.freeze(rb, vs, wt, A, 1.5);
    CHECK(std::memcmp(&ea, &eb, sizeof(double)) == 0);
    CHECK(std::memcmp(&ra, &rb, sizeof(ra)) == 0);
  }
  CHECK(multi > 100);  // both the four-piece and the one-piece (gentle turn) paths were compared
  CHECK(single > 10);
}

TEST_CASE("line-blend kernels: arc-length table and curvature agree with the Bezier evaluated directly") {
  const auto& k = detail::line_blend_kernels();
  const auto& T = detail::line_blend_tables();
  std::mt19937 rng(11);
  for (int trial = 0; trial < 50; ++trial) {
    const Vec3 u1 = random_unit(rng), u2 = random_unit(rng);
    const double d = 0.5;
    const Vec3 vtx(1, 2, 3);
    Segment s;
    detail::LineBlendRecord r;
    k.build(T, s, vtx - d * u1, vtx, vtx + d * u2, u1, u2, d, 0, Vec3(3000, 3000, 3000), Vec3(250, 250, 250),
            Vec3::Constant(1 / 3000.0), 1e9, 1e9, r);
    // the same control points through Segment::blend (general Bezier code, 17-node table)
    const Segment g = Segment::blend(s.ctrl[0], s.ctrl[1], s.ctrl[2], s.ctrl[3], 0);
    for (int i = 0; i <= 16; ++i) CHECK(s.table[i] == doctest::Approx(g.table[i]).epsilon(1e-6));
    CHECK(s.curvature == doctest::Approx(g.curvature).epsilon(1e-6));
    // the pieces tile the blend: trims match the table at detail::cuts_lines
    if (r.np == detail::n_cuts_lines) {
      for (int p = 0; p < r.np; ++p) {
        CHECK(r.trim_s[p] == s.table[detail::cuts_lines[p]]);
        CHECK(r.len[p] == doctest::Approx(s.table[detail::cuts_lines[p + 1]] - s.table[detail::cuts_lines[p]]));
      }
    }
  }
}
