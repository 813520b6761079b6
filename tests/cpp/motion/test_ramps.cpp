// The per-direction terms of the axis box (Node::ramp_tangent, ramp_curvature): for a speed change
// along the path at v² with the largest tangential acceleration the terms allow, every axis stays
// within its limit at every point of the piece, checked against the exact tangent and curvature
// vector of densely sampled cubic Béziers and arcs (not the 17-node table the terms come from).
#include <doctest/doctest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <random>
#include <string>

#include "motion/planner/blend_bounds.hpp"
#include "motion/kernels/cubic_record_kernels.hpp"
#include "motion/planner/geometry.hpp"
#include "netshape/motion.hpp"

using namespace netshape;
using namespace netshape::motion;
using namespace netshape::motion::detail;

namespace {

// Largest |u_i·a + κn_i·v²| / A over samples (u, κn) for a = ±(largest tangential acceleration the
// terms allow at v²), both directions, over a range of speeds up to the cap; also checks that each
// term is at most the unsigned one.
double worst_ratio(const std::vector<Vec3>& tangents, const std::vector<Vec3>& curvatures, const Vec3& U, const Vec3& K,
                   const Vec3 (&Ua)[2], const Vec3 (&Ka)[2], const Vec3& A) {
  double wcap = 1e300;
  for (int i = 0; i < 3; ++i)
    if (K[i] > 0) wcap = std::min(wcap, A[i] / K[i]);
  if (!(wcap < 1e300)) wcap = 1e6;
  double worst = 0;
  for (int d = 0; d < 2; ++d) {
    for (int i = 0; i < 3; ++i) {
      CHECK(Ua[d][i] <= U[i]);
      CHECK(Ka[d][i] <= K[i]);
    }
    for (const double f : {0.0, 0.1, 0.3, 0.5, 0.7, 0.9, 0.99}) {
      const double w = f * wcap;
      double a = 1e300;
      for (int i = 0; i < 3; ++i)
        if (Ua[d][i] > 0) a = std::min(a, (A[i] - Ka[d][i] * w) / Ua[d][i]);
      if (!(a > 0) || !(a < 1e300)) continue;
      const double sa = d == 0 ? a : -a;
      for (std::size_t k = 0; k < tangents.size(); ++k)
        for (int i = 0; i < 3; ++i)
          worst = std::max(worst, std::abs(tangents[k][i] * sa + curvatures[k][i] * w) / A[i]);
    }
  }
  return worst;
}

}  // namespace

TEST_CASE("ramp terms of cubic pieces keep every axis within its limit (random cubics, every run of intervals)") {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> U01(-1.0, 1.0);
  const Vec3 A(3000.0, 2000.0, 1500.0);
  double worst = 0;
  int tighter = 0, pieces = 0;
  for (int trial = 0; trial < 40; ++trial) {
    const Vec3 p0(0, 0, 0);
    const Vec3 p1 = p0 + Vec3(1.0 + 0.5 * U01(rng), 0.6 * U01(rng), 0.3 * U01(rng));
    const Vec3 p2 = p1 + Vec3(0.8 * U01(rng), 1.0 + 0.5 * U01(rng), 0.3 * U01(rng));
    const Vec3 p3 = p2 + Vec3(0.6 * U01(rng) - 0.5, 0.5 * U01(rng) + 0.5, 0.3 * U01(rng));
    std::array<Vec3, 17> T, Kv;
    const Segment g = Segment::blend(p0, p1, p2, p3, 0, &T, &Kv);
    BlendBounds tab;
    cubic_record_kernels().fill(tab, T[0].data(), Kv[0].data());
    for (const auto& [r0, r1] : {std::pair{0, 16}, std::pair{0, 1}, std::pair{3, 7}, std::pair{8, 12}, std::pair{15, 16},
                                 std::pair{5, 6}}) {
      Vec3 U, K, Ua[2], Ka[2];
      tab.bounds(r0, r1, U, K);
      tab.ramps(r0, r1, U, K, Ua, Ka);
      std::vector<Vec3> ts, ks;
      const double s0 = g.table[static_cast<std::size_t>(r0)], s1 = g.table[static_cast<std::size_t>(r1)];
      for (int q = 0; q <= 400; ++q) {
        const double u = g.bezier_u(s0 + (s1 - s0) * q / 400.0);
        const Vec3 d1 = bezier_d1(g.ctrl, u), d2 = bezier_d2(g.ctrl, u);
        const double n2 = d1.squaredNorm();
        ts.push_back(d1 / std::sqrt(n2));
        ks.push_back((d2 - d1 * (d1.dot(d2) / n2)) / n2);
      }
      worst = std::max(worst, worst_ratio(ts, ks, U, K, Ua, Ka, A));
      ++pieces;
      if ((Ua[0] - U).norm() + (Ka[0] - K).norm() + (Ua[1] - U).norm() + (Ka[1] - K).norm() > 1e-9) ++tighter;
    }
  }
  CHECK(worst <= 1.0 + 1e-9);
  // the signed terms are tighter than the unsigned box on most pieces (that is what they are for)
  CHECK(tighter > pieces / 2);
}

namespace {
// BlendBounds' rows as defined (the kernel computes them a packet at a time): per axis and table
// interval r the maxima over its two nodes of |x| and of the absolute second differences
// |(x[i−1] − 2·x[i]) + x[i+1]| of |x| (0 at the end nodes), the largest and smallest x and the largest
// second difference of x, for x the unit tangent's and the curvature vector's component
void reference_fill(BlendBounds& t, const std::array<Vec3, 17>& T, const std::array<Vec3, 17>& Kv) {
  const auto rows = [](const double (&x)[17], double* amax, double* a2max, double* hi, double* lo, double* s2max) {
    double a[17], da[17] = {}, dx[17] = {};
    for (int i = 0; i < 17; ++i) a[i] = std::abs(x[i]);
    for (int i = 1; i < 16; ++i) {
      da[i] = std::abs(a[i - 1] - 2.0 * a[i] + a[i + 1]);
      dx[i] = std::abs(x[i - 1] - 2.0 * x[i] + x[i + 1]);
    }
    for (int r = 0; r < 16; ++r) {
      amax[r] = std::max(a[r], a[r + 1]);
      a2max[r] = std::max(da[r], da[r + 1]);
      hi[r] = std::max(x[r], x[r + 1]);
      lo[r] = std::min(x[r], x[r + 1]);
      s2max[r] = std::max(dx[r], dx[r + 1]);
    }
  };
  for (int c = 0; c < 3; ++c) {
    double ts[17], ks[17];
    for (std::size_t i = 0; i < 17; ++i) {
      ts[i] = T[i][c];
      ks[i] = Kv[i][c];
    }
    rows(ts, t.mu[c], t.du[c], t.tmax[c], t.tmin[c], t.st[c]);
    rows(ks, t.mk[c], t.dk[c], t.kmax[c], t.kmin[c], t.sk[c]);
  }
}

// The node frames (unit tangent, curvature vector) of a random cubic from the origin: planar when
// trial % 3 == 0 (an axis whose terms are all zero), with a straight part when trial % 5 == 0.
void random_cubic_frames(std::mt19937& rng, int trial, std::array<Vec3, 17>& T, std::array<Vec3, 17>& Kv) {
  std::uniform_real_distribution<double> U01(-1.0, 1.0);
  const Vec3 p0(0, 0, 0);
  const double z = trial % 3 == 0 ? 0.0 : 0.4;
  const Vec3 p1 = p0 + Vec3(1.0 + 0.5 * U01(rng), 0.6 * U01(rng), z * U01(rng));
  const Vec3 p2 = trial % 5 == 0 ? Vec3(2.0 * p1) : Vec3(p1 + Vec3(0.8 * U01(rng), 1.0 + 0.5 * U01(rng), z * U01(rng)));
  const Vec3 p3 = p2 + Vec3(0.6 * U01(rng) - 0.5, 0.5 * U01(rng) + 0.5, z * U01(rng));
  Segment::blend(p0, p1, p2, p3, 0, &T, &Kv);
}

// every per-interval row of a and b the same bits
void check_same_rows(const BlendBounds& a, const BlendBounds& b) {
  CHECK(std::memcmp(a.mu, b.mu, sizeof a.mu) == 0);
  CHECK(std::memcmp(a.mk, b.mk, sizeof a.mk) == 0);
  CHECK(std::memcmp(a.du, b.du, sizeof a.du) == 0);
  CHECK(std::memcmp(a.dk, b.dk, sizeof a.dk) == 0);
  CHECK(std::memcmp(a.tmax, b.tmax, sizeof a.tmax) == 0);
  CHECK(std::memcmp(a.tmin, b.tmin, sizeof a.tmin) == 0);
  CHECK(std::memcmp(a.kmax, b.kmax, sizeof a.kmax) == 0);
  CHECK(std::memcmp(a.kmin, b.kmin, sizeof a.kmin) == 0);
  CHECK(std::memcmp(a.st, b.st, sizeof a.st) == 0);
  CHECK(std::memcmp(a.sk, b.sk, sizeof a.sk) == 0);
}

// bounds U, K and ramp terms Ua, Ka of two computations the same bits
void check_same_terms(const Vec3& U, const Vec3& K, const Vec3 (&Ua)[2], const Vec3 (&Ka)[2], const Vec3& U1,
                      const Vec3& K1, const Vec3 (&Ua1)[2], const Vec3 (&Ka1)[2]) {
  CHECK(std::memcmp(U.data(), U1.data(), sizeof(double) * 3) == 0);
  CHECK(std::memcmp(K.data(), K1.data(), sizeof(double) * 3) == 0);
  for (int d = 0; d < 2; ++d) {
    CHECK(std::memcmp(Ua[d].data(), Ua1[d].data(), sizeof(double) * 3) == 0);
    CHECK(std::memcmp(Ka[d].data(), Ka1[d].data(), sizeof(double) * 3) == 0);
  }
}
}  // namespace

TEST_CASE("the cubic-record kernel's BlendBounds rows and BlendBounds::whole are as defined, bit for bit") {
  MESSAGE("cubic-record kernels in use: " << std::string(cubic_record_kernels().isa));
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> U01(-1.0, 1.0);
  for (int trial = 0; trial < 200; ++trial) {
    std::array<Vec3, 17> T, Kv;
    random_cubic_frames(rng, trial, T, Kv);
    BlendBounds a, b;
    cubic_record_kernels().fill(a, T[0].data(), Kv[0].data());
    reference_fill(b, T, Kv);
    check_same_rows(a, b);
    Vec3 U, K, Ua[2], Ka[2], U1, K1, Ua1[2], Ka1[2];
    a.bounds(0, 16, U, K);
    a.ramps(0, 16, U, K, Ua, Ka);
    a.whole(U1, K1, Ua1, Ka1);
    check_same_terms(U, K, Ua, Ka, U1, K1, Ua1, Ka1);
  }
}

TEST_CASE("the cubic-record kernel's cubic_node gives Segment::blend's table and curvatures and the rows, bit for bit") {
  std::mt19937 rng(13);
  std::uniform_real_distribution<double> U01(-1.0, 1.0);
  int symmetric = 0;
  for (int trial = 0; trial < 300; ++trial) {
    // random cubics (some planar, some with P1 = P2 or a straight part, some symmetric blends)
    const Vec3 p0(10 * U01(rng), 10 * U01(rng), 10 * U01(rng));
    const double z = trial % 3 == 0 ? 0.0 : 0.4, scale = trial % 4 == 0 ? 1e-3 : 1.0;
    const Vec3 p1 = p0 + scale * Vec3(1.0 + 0.5 * U01(rng), 0.6 * U01(rng), z * U01(rng));
    Vec3 p2 = trial % 5 == 0 ? Vec3(p1 + (p1 - p0)) : Vec3(p1 + scale * Vec3(0.8 * U01(rng), 1.0 + 0.5 * U01(rng), z * U01(rng)));
    Vec3 p3 = p2 + scale * Vec3(0.6 * U01(rng) - 0.5, 0.5 * U01(rng) + 0.5, z * U01(rng));
    if (trial % 7 == 0) {  // a blend between two lines: P1 = P2, |P1 − P0| = |P3 − P2|
      p2 = p1;
      p3 = p1 + (p1 - p0).norm() * Vec3(0.0, 1.0, 0.0);
    }
    std::array<Vec3, 17> T, Kv;
    const Segment g = Segment::blend(p0, p1, p2, p3, 0, &T, &Kv);
    BlendBounds a, b;
    reference_fill(b, T, Kv);
    const std::array<Vec3, 4> P{p0, p1, p2, p3};
    std::array<double, 17> table{};
    double k_at[17];
    double folds[3][10], finish[2];
    if (!cubic_record_kernels().cubic_node(P[0].data(), table.data(), k_at, a, folds, finish)) {
      ++symmetric;
      continue;
    }
    CHECK(std::memcmp(table.data(), g.table.data(), sizeof table) == 0);
    REQUIRE(finish[0] >= 0);
    CHECK(std::memcmp(&finish[0], &g.curvature, sizeof(double)) == 0);
    CHECK(std::memcmp(&finish[1], &g.curvature_rate, sizeof(double)) == 0);
    for (std::size_t i = 0; i < 17; ++i) {
      const double k = Kv[i].norm();
      CHECK(std::memcmp(&k_at[i], &k, sizeof k) == 0);
    }
    check_same_rows(a, b);
    Vec3 U, K, Ua[2], Ka[2], U1, K1, Ua1[2], Ka1[2];
    b.bounds(0, 16, U, K);
    b.ramps(0, 16, U, K, Ua, Ka);
    BlendBounds::whole_from(folds, U1, K1, Ua1, Ka1);
    check_same_terms(U, K, Ua, Ka, U1, K1, Ua1, Ka1);
  }
  CHECK(symmetric >= 40);  // the blends between two lines are left to Segment::blend
}

TEST_CASE("the cubic-record kernel's record_singles gives each piece bounds(), ramps() and piece_curvature(), bit for bit") {
  std::mt19937 rng(17);
  std::uniform_real_distribution<double> U01(-1.0, 1.0);
  for (int trial = 0; trial < 200; ++trial) {
    const Vec3 p0(0, 0, 0);
    const double z = trial % 3 == 0 ? 0.0 : 0.4;
    const Vec3 p1 = p0 + Vec3(1.0 + 0.5 * U01(rng), 0.6 * U01(rng), z * U01(rng));
    const Vec3 p2 = trial % 5 == 0 ? Vec3(2.0 * p1) : Vec3(p1 + Vec3(0.8 * U01(rng), 1.0 + 0.5 * U01(rng), z * U01(rng)));
    const Vec3 p3 = p2 + Vec3(0.6 * U01(rng) - 0.5, 0.5 * U01(rng) + 0.5, z * U01(rng));
    std::array<Vec3, 17> T, Kv;
    const Segment g = Segment::blend(p0, p1, p2, p3, 0, &T, &Kv);
    BlendBounds tab;
    cubic_record_kernels().fill(tab, T[0].data(), Kv[0].data());
    double k_at[17];
    for (std::size_t i = 0; i < 17; ++i) k_at[i] = Kv[i].norm();
    CubicRecord r;
    r.np = 1 + trial % 16;
    const int r0 = (trial / 16) % (17 - r.np);
    cubic_record_kernels().record_singles(tab, k_at, g.table.data(), r0, r);
    for (int k = 0; k < r.np; ++k) {
      Vec3 U, K, Ua[2], Ka[2];
      tab.bounds(r0 + k, r0 + k + 1, U, K);
      tab.ramps(r0 + k, r0 + k + 1, U, K, Ua, Ka);
      double kmax, rate;
      piece_curvature(k_at, g.table, r0 + k, r0 + k + 1, kmax, rate);
      for (int c = 0; c < 3; ++c) {
        CHECK(std::memcmp(&r.u_abs[c][k], &U[c], sizeof(double)) == 0);
        CHECK(std::memcmp(&r.k_abs[c][k], &K[c], sizeof(double)) == 0);
        for (int d = 0; d < 2; ++d) {
          CHECK(std::memcmp(&r.ramp_u[d][c][k], &Ua[d][c], sizeof(double)) == 0);
          CHECK(std::memcmp(&r.ramp_k[d][c][k], &Ka[d][c], sizeof(double)) == 0);
        }
      }
      CHECK(std::memcmp(&r.curvature[k], &kmax, sizeof(double)) == 0);
      CHECK(std::memcmp(&r.curvature_rate[k], &rate, sizeof(double)) == 0);
    }
  }
}

TEST_CASE("the cubic-record kernel's singles give bounds() and ramps() of every single interval, bit for bit") {
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> U01(-1.0, 1.0);
  for (int trial = 0; trial < 200; ++trial) {
    // random cubics, some planar (an axis whose terms are all zero) and some with a straight part
    std::array<Vec3, 17> T, Kv;
    random_cubic_frames(rng, trial, T, Kv);
    BlendBounds tab;
    cubic_record_kernels().fill(tab, T[0].data(), Kv[0].data());
    cubic_record_kernels().singles(tab);
    for (int r = 0; r < 16; ++r) {
      Vec3 U, K, Ua[2], Ka[2], U1, K1, Ua1[2], Ka1[2];
      tab.bounds(r, r + 1, U, K);
      tab.ramps(r, r + 1, U, K, Ua, Ka);
      tab.single(r, U1, K1, Ua1, Ka1);
      for (int c = 0; c < 3; ++c) {
        CHECK(std::signbit(U1[c]) == std::signbit(U[c]));
        CHECK(U1[c] == U[c]);
        CHECK(K1[c] == K[c]);
        for (int d = 0; d < 2; ++d) {
          CHECK(Ua1[d][c] == Ua[d][c]);
          CHECK(Ka1[d][c] == Ka[d][c]);
          CHECK(std::signbit(Ka1[d][c]) == std::signbit(Ka[d][c]));
        }
      }
    }
  }
}

TEST_CASE("ramp terms of arc pieces keep every axis within its limit (both senses, helices, every quadrant)") {
  const Vec3 A(3000.0, 3000.0, 1000.0);
  double worst = 0;
  for (const bool cw : {false, true})
    for (const double dz : {0.0, 0.7})
      for (const double start_angle : {0.0, 0.4, 1.9, 3.5, 5.0}) {
        toolpath::Block b;
        b.kind = toolpath::MotionKind::arc;
        b.plane = toolpath::Plane::xy;
        b.clockwise = cw;
        b.turns = 1;
        b.feed = 100.0;
        const double r = 2.0, sweep = cw ? -2.5 : 2.5;
        b.center = Vec3(1.0, -1.0, 0.0);
        b.start = b.center + Vec3(r * std::cos(start_angle), r * std::sin(start_angle), 0.0);
        b.end = b.center + Vec3(r * std::cos(start_angle + sweep), r * std::sin(start_angle + sweep), dz);
        const Segment s = Segment::arc(b, 0);
        const int m = 5;
        for (int k = 0; k < m; ++k) {
          const double s0 = s.full_length * k / m, s1 = s.full_length * (k + 1) / m;
          Vec3 U, K, Ua[2], Ka[2];
          arc_bounds(s, s0, s1, U, K, Ua, Ka);
          std::vector<Vec3> ts, ks;
          for (int q = 0; q <= 400; ++q) {
            const double f = (s0 + (s1 - s0) * q / 400.0) / s.full_length;
            const double phi = start_angle + sweep * f;
            // helix: p = c + r(cos φ, sin φ) + dz·f; dp/df = (−r·sw·sin φ, r·sw·cos φ, dz)
            const Vec3 d1(-r * sweep * std::sin(phi), r * sweep * std::cos(phi), dz);
            const Vec3 d2(-r * sweep * sweep * std::cos(phi), -r * sweep * sweep * std::sin(phi), 0.0);
            const double n2 = d1.squaredNorm();
            ts.push_back(d1 / std::sqrt(n2));
            ks.push_back((d2 - d1 * (d1.dot(d2) / n2)) / n2);
          }
          worst = std::max(worst, worst_ratio(ts, ks, U, K, Ua, Ka, A));
        }
      }
  CHECK(worst <= 1.0 + 1e-9);
}
