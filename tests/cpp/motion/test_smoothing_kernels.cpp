// netshape::motion smoothing kernels (src/motion/kernels/smoothing_kernels.hpp): every copy gives the bits of the
// scalar definition, and the copy of the chosen instruction set the same bits as the baseline one.
#include <doctest/doctest.h>

#include <algorithm>
#include <cstring>
#include <random>
#include <string>
#include <vector>

#include "motion/kernels/smoothing_kernels.hpp"

using namespace netshape::motion;

namespace {
// The definition: the power form of the basis on span k by the Cox–de Boor recursion on polynomials in
// x = u − t[k] (Spline::power_basis(), one span at a time).
void power_basis_span(const double* t, int k, double* b) {
  std::fill(b, b + 16, 0.0);
  const double tk = t[k];
  if (!(t[k + 1] > tk)) return;
  double d[8];
  for (int q = 0; q < 8; ++q) d[q] = t[k - 3 + q] - tk;
  double N[4][4] = {{1, 0, 0, 0}};
  for (int p = 1; p <= 3; ++p) {
    double M[4][4] = {};
    for (int r = 0; r <= p; ++r) {
      const double a0 = d[3 - p + r], a1 = d[3 + r], b0 = d[4 - p + r], b1 = d[4 + r];
      if (r >= 1 && a1 > a0) {
        const double f = 1.0 / (a1 - a0);
        const double* n = N[r - 1];
        M[r][0] += f * (-a0 * n[0]);
        M[r][1] += f * (n[0] - a0 * n[1]);
        M[r][2] += f * (n[1] - a0 * n[2]);
        M[r][3] += f * (n[2] - a0 * n[3]);
      }
      if (r < p && b1 > b0) {
        const double f = 1.0 / (b1 - b0);
        const double* n = N[r];
        M[r][0] += f * (b1 * n[0]);
        M[r][1] += f * (b1 * n[1] - n[0]);
        M[r][2] += f * (b1 * n[2] - n[1]);
        M[r][3] += f * (b1 * n[3] - n[2]);
      }
    }
    std::copy(&M[0][0], &M[0][0] + 16, &N[0][0]);
  }
  for (int j = 0; j < 4; ++j)
    for (int r = 0; r < 4; ++r) b[4 * j + r] = N[r][j];
}

bool same(const std::vector<double>& a, const std::vector<double>& b) {
  return a.size() == b.size() && std::memcmp(a.data(), b.data(), sizeof(double) * a.size()) == 0;
}
}  // namespace

TEST_CASE("smoothing kernels: power_basis gives the definition's bits in every copy") {
  const auto& best = detail::smoothing_kernels();
  const auto& plain = detail::smoothing_kernels_plain();
  MESSAGE("smoothing kernels in use: " << std::string(best.isa));
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> uni(0.0, 1.0);
  int empty_spans = 0, tails = 0;
  for (int trial = 0; trial < 300; ++trial) {
    // a clamped knot vector: 4 equal at each end, interior knots with repeats and near-repeats
    const int inner = static_cast<int>(uni(rng) * 30);
    std::vector<double> t(4, 0.0);
    double u = 0;
    for (int i = 0; i < inner; ++i) {
      const double c = uni(rng);
      u += c < 0.15 ? 0.0 : c < 0.25 ? 1e-12 * uni(rng) : (trial % 3 == 0 ? 1.0 : 3.0 * uni(rng));
      t.push_back(u);
    }
    const double L = u + 0.5 + uni(rng);
    t.insert(t.end(), 4, L);
    const int m = static_cast<int>(t.size()) - 4;  // control points; spans 3..m − 1
    const int k0 = 3 + static_cast<int>(uni(rng) * (m - 3));
    const int k1 = k0 + static_cast<int>(uni(rng) * (m - k0));
    tails += (k1 - k0 + 1) % 4 != 0;
    // the definition on k0..k1, a marker elsewhere (the kernels write k0..k1 only)
    std::vector<double> want(16 * static_cast<std::size_t>(m), 7.0), x = want, y = want;
    for (int k = k0; k <= k1; ++k) {
      power_basis_span(t.data(), k, want.data() + 16 * k);
      empty_spans += !(t[static_cast<std::size_t>(k) + 1] > t[static_cast<std::size_t>(k)]);
    }
    plain.power_basis(t.data(), k0, k1, x.data());
    best.power_basis(t.data(), k0, k1, y.data());
    CHECK(same(x, want));
    CHECK(same(y, want));
  }
  CHECK(empty_spans > 50);
  CHECK(tails > 100);
}

namespace {
// The definition: dist2() of point (x, y) to segment q (smoothing/spline.hpp), then the minima over
// the window as the chain check's bounds fold them, one segment after the other.
double dist2_def(double x, double y, const detail::SegRows& s, long q) {
  const double rx = x - s.ax[q], ry = y - s.ay[q];
  const double t = std::clamp((rx * s.dx[q] + ry * s.dy[q]) * s.il2[q], 0.0, 1.0);
  const double ex = rx - t * s.dx[q], ey = ry - t * s.dy[q];
  return ex * ex + ey * ey;
}
}  // namespace

TEST_CASE("smoothing kernels: pair_window gives the definition's bits in every copy") {
  const auto& best = detail::smoothing_kernels();
  const auto& plain = detail::smoothing_kernels_plain();
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> uni(-1.0, 1.0);
  int points = 0, clamped = 0;
  for (int trial = 0; trial < 400; ++trial) {
    // a chain of segments, some of them points (il2 = 0)
    const long n = 1 + static_cast<long>(40 * (0.5 + 0.5 * uni(rng)));
    std::vector<double> ax, ay, dx, dy, il2, sag;
    double x = 0, y = 0;
    for (long q = 0; q < n; ++q) {
      const bool point = uni(rng) > 0.8;
      const double ex = point ? 0.0 : uni(rng), ey = point ? 0.0 : uni(rng);
      const double l2 = ex * ex + ey * ey;
      ax.push_back(x);
      ay.push_back(y);
      dx.push_back(ex);
      dy.push_back(ey);
      il2.push_back(l2 > 0 ? 1.0 / l2 : 0.0);
      sag.push_back(trial % 5 == 0 ? 0.0 : 0.01 * (1.0 + uni(rng)));
      points += point;
      x += ex;
      y += ey;
    }
    const detail::SegRows s{ax.data(), ay.data(), dx.data(), dy.data(), il2.data()};
    const long lo = static_cast<long>((n - 1) * (0.5 + 0.5 * uni(rng)));
    const long hi = lo + static_cast<long>((n - 1 - lo) * (0.5 + 0.5 * uni(rng)));
    const double p[4] = {x * (0.5 + 0.5 * uni(rng)) + uni(rng), y * (0.5 + 0.5 * uni(rng)) + uni(rng), uni(rng) * 3, uni(rng) * 3};
    const std::size_t len = static_cast<std::size_t>(hi - lo + 1);
    // the definition
    std::vector<double> W0(len + 9, 5.0), W1 = W0;
    double want[5] = {1e300, 1e300, 1e300, 1e300, 1e300};
    for (long q = lo; q <= hi; ++q) {
      const auto i = static_cast<std::size_t>(q - lo);
      W0[i] = dist2_def(p[0], p[1], s, q);
      W1[i] = dist2_def(p[2], p[3], s, q);
      const double c = (p[0] - ax[q]) * dx[q] + (p[1] - ay[q]) * dy[q];
      clamped += il2[q] > 0 && (c < 0 || c * il2[q] > 1);
      want[0] = std::min(want[0], std::max(W0[i], W1[i]));
      want[1] = std::min(want[1], W0[i]);
      want[2] = std::min(want[2], W1[i]);
      want[3] = std::min(want[3], std::sqrt(std::max(W0[i], W1[i])) + sag[static_cast<std::size_t>(q)]);
      want[4] = std::min(want[4], sag[static_cast<std::size_t>(q)]);
    }
    for (const auto* k : {&plain, &best}) {
      for (const bool with_sag : {false, true}) {
        std::vector<double> D0(len + 9, 5.0), D1 = D0;  // 5.0 past hi: nothing is written there
        double mins[5] = {-1, -1, -1, -1, -1};
        k->pair_window(p, s, lo, hi, with_sag ? sag.data() : nullptr, D0.data(), D1.data(), mins);
        CHECK(same(D0, W0));
        CHECK(same(D1, W1));
        CHECK(std::memcmp(mins, want, sizeof(double) * (with_sag ? 5 : 3)) == 0);
        if (!with_sag) CHECK(mins[3] == -1);
      }
    }
  }
  CHECK(points > 100);
  CHECK(clamped > 100);
}

namespace {
// The definition: Spline::span_near() and Spline::eval() on the power form, and fit_run()'s Newton
// steps to a point's foot, one point at a time.
int span_near_def(const std::vector<double>& t, int m, double u, int k) {
  if (u >= t[static_cast<std::size_t>(m)]) return m - 1;
  k = std::clamp(k, 3, m - 1);
  for (int step = 0; step < 4; ++step) {
    if (u < t[static_cast<std::size_t>(k)]) {
      if (k == 3) return 3;
      --k;
    } else if (u >= t[static_cast<std::size_t>(k + 1)]) {
      ++k;
    } else {
      return k;
    }
  }
  return static_cast<int>(std::upper_bound(t.begin() + 3, t.begin() + m + 1, u) - t.begin()) - 1;
}

struct FootDef {
  double u;
  int k;
  double res;
};

FootDef foot_def(const std::vector<double>& t, const std::vector<double>& pw, int m, double L, double mean, double u,
                 int k, double px, double py) {
  double du = 0, r_old = 0, s0[2] = {}, s1[2] = {}, s2[2] = {};
  int k_old = k;
  for (int it = 0;; ++it) {
    k = span_near_def(t, m, u, k);
    const double* c = pw.data() + 8 * k;
    const double x = u - t[static_cast<std::size_t>(k)];
    for (int d = 0; d < 2; ++d) {
      s0[d] = c[d] + x * (c[2 + d] + x * (c[4 + d] + x * c[6 + d]));
      s1[d] = c[2 + d] + x * (2.0 * c[4 + d] + x * (3.0 * c[6 + d]));
      s2[d] = 2.0 * c[4 + d] + (6.0 * x) * c[6 + d];
    }
    const double rx = s0[0] - px, ry = s0[1] - py;
    if (it == 0) {
      k_old = k;
      r_old = std::sqrt(rx * rx + ry * ry);
    } else if (it == 2 || std::abs(du) < 1e-9) {
      break;
    }
    const double fp = (s1[0] * s1[0] + s1[1] * s1[1]) + (rx * s2[0] + ry * s2[1]);
    if (!(fp > 0)) break;
    du = std::clamp(-(rx * s1[0] + ry * s1[1]) / fp, -0.25 * mean, 0.25 * mean);
    u = std::clamp(u + du, 0.0, L);
  }
  const double rx = s0[0] - px, ry = s0[1] - py;
  const double res = std::sqrt(rx * rx + ry * ry);
  if (res <= r_old) return {u, k, res};
  return {-1.0, k_old, r_old};  // u unchanged
}
}  // namespace

TEST_CASE("smoothing kernels: foot_points gives the definition's bits in every copy") {
  const auto& best = detail::smoothing_kernels();
  const auto& plain = detail::smoothing_kernels_plain();
  std::mt19937 rng(17);
  std::uniform_real_distribution<double> uni(0.0, 1.0);
  int moved = 0, kept = 0, span_changes = 0;
  for (int trial = 0; trial < 200; ++trial) {
    // clamped knots with some empty spans, and a random cubic on each span (continuity does not matter)
    const int inner = 3 + static_cast<int>(uni(rng) * 20);
    std::vector<double> t(4, 0.0);
    double u = 0;
    for (int i = 0; i < inner; ++i) {
      u += uni(rng) < 0.1 ? 0.0 : 0.2 + uni(rng);
      t.push_back(u);
    }
    const double L = u + 0.2 + uni(rng);
    t.insert(t.end(), 4, L);
    const int m = static_cast<int>(t.size()) - 4;
    std::vector<double> pw(8 * static_cast<std::size_t>(m), 0.0);
    for (int k = 3; k < m; ++k)
      for (int j = 0; j < 8; ++j) pw[static_cast<std::size_t>(8 * k + j)] = (j < 2 ? t[static_cast<std::size_t>(k)] : 0.0) + (uni(rng) - 0.5) * (j < 4 ? 1.0 : 0.3);
    const double mean = 0.2 + uni(rng);
    const int n = 1 + static_cast<int>(uni(rng) * 40);
    std::vector<double> u0, px, py;
    std::vector<int> k0;
    for (int i = 0; i < n; ++i) {
      u0.push_back(uni(rng) * L);
      k0.push_back(3 + static_cast<int>(uni(rng) * (m - 3)));  // any span to start the search from
      px.push_back(u0.back() + (uni(rng) - 0.5) * (i % 7 == 0 ? 20.0 : 0.5));
      py.push_back((uni(rng) - 0.5) * (i % 7 == 0 ? 20.0 : 0.5));
    }
    const detail::FootSpline f{t.data(), pw.data(), m, L, mean};
    for (const auto* kern : {&plain, &best}) {
      std::vector<double> uu = u0, res(static_cast<std::size_t>(n), -7.0);
      std::vector<int> kk = k0;
      kern->foot_points(f, n, uu.data(), kk.data(), px.data(), py.data(), res.data());
      for (int i = 0; i < n; ++i) {
        const auto ui = static_cast<std::size_t>(i);
        FootDef want = foot_def(t, pw, m, L, mean, u0[ui], k0[ui], px[ui], py[ui]);
        if (want.u < 0) want.u = u0[ui];
        CHECK(std::memcmp(&uu[ui], &want.u, sizeof(double)) == 0);
        CHECK(kk[ui] == want.k);
        CHECK(std::memcmp(&res[ui], &want.res, sizeof(double)) == 0);
        if (kern == &plain) {
          moved += uu[ui] != u0[ui];
          kept += uu[ui] == u0[ui];
          span_changes += kk[ui] != k0[ui];
        }
      }
    }
  }
  CHECK(moved > 200);
  CHECK(kept > 20);
  CHECK(span_changes > 200);
}

TEST_CASE("smoothing kernels: run_parts gives the definition's bits in every copy") {
  const auto& best = detail::smoothing_kernels();
  const auto& plain = detail::smoothing_kernels_plain();
  std::mt19937 rng(23);
  std::uniform_real_distribution<double> uni(-1.0, 1.0);
  int cut_inside = 0, cut_clamped = 0;
  for (int trial = 0; trial < 400; ++trial) {
    // a chain with bisectors at its vertices (some degenerate: a zero or parallel direction)
    const long n = 1 + static_cast<long>(30 * (0.5 + 0.5 * uni(rng)));
    std::vector<double> ax, ay, dx, dy, il2, wx, wy, sag;
    double x = 0, y = 0;
    for (long q = 0; q < n; ++q) {
      const bool point = uni(rng) > 0.85;
      const double ex = point ? 0.0 : 0.5 + 0.5 * uni(rng), ey = point ? 0.0 : uni(rng);
      const double l2 = ex * ex + ey * ey;
      ax.push_back(x);
      ay.push_back(y);
      dx.push_back(ex);
      dy.push_back(ey);
      il2.push_back(l2 > 0 ? 1.0 / l2 : 0.0);
      sag.push_back(0.01 * (1.0 + uni(rng)));
      const double r = uni(rng);
      wx.push_back(r > 0.9 ? 0.0 : uni(rng));
      wy.push_back(r > 0.9 ? 0.0 : 1.0 + uni(rng));
      x += ex;
      y += ey;
    }
    const detail::SegRows s{ax.data(), ay.data(), dx.data(), dy.data(), il2.data(), wx.data(), wy.data()};
    const long lo = static_cast<long>((n - 1) * (0.5 + 0.5 * uni(rng)));
    const long hi = lo + static_cast<long>((n - 1 - lo) * (0.5 + 0.5 * uni(rng)));
    const double c[4] = {ax[static_cast<std::size_t>(lo)] + 0.2 * uni(rng), 0.3 * uni(rng), x + 0.2 * uni(rng), y + 0.3 * uni(rng)};
    const std::size_t len = static_cast<std::size_t>(hi - lo + 1);
    std::vector<double> D0(len), D1(len);
    for (long q = lo; q <= hi; ++q) {
      D0[static_cast<std::size_t>(q - lo)] = dist2_def(c[0], c[1], s, q);
      D1[static_cast<std::size_t>(q - lo)] = dist2_def(c[2], c[3], s, q);
    }
    for (const bool with_sag : {false, true}) {
      // the definition, one segment and one vertex at a time (run_bound()'s loop)
      const auto val = [&](double d2, long q) { return with_sag ? std::sqrt(d2) + sag[static_cast<std::size_t>(q)] : d2; };
      std::vector<double> W0(len + 9, 5.0), W1 = W0, WN = W0, WX = W0;
      const double ex = c[2] - c[0], ey = c[3] - c[1];
      for (long q = lo; q <= hi; ++q) {
        const auto i = static_cast<std::size_t>(q - lo);
        W0[i] = val(D0[i], q);
        W1[i] = val(D1[i], q);
        if (q == hi) break;
        const auto u = static_cast<std::size_t>(q);
        const double bx = ax[u + 1] - c[0], by = ay[u + 1] - c[1];
        double t = (bx * wy[u] - by * wx[u]) / (ex * wy[u] - ey * wx[u]);
        if (!(t >= 0)) t = 0;
        if (!(t <= 1)) t = 1;
        cut_inside += t > 0 && t < 1;
        cut_clamped += t == 0 || t == 1;
        const double px = c[0] + t * ex, py = c[1] + t * ey;
        WN[i] = val(dist2_def(px, py, s, q), q);
        WX[i] = val(dist2_def(px, py, s, q + 1), q + 1);
      }
      for (const auto* k : {&plain, &best}) {
        std::vector<double> V0(len + 9, 5.0), V1 = V0, VN = V0, VX = V0;  // 5.0 past the ranges: nothing is written there
        k->run_parts(c, s, lo, hi, with_sag ? sag.data() : nullptr, D0.data(), D1.data(), V0.data(), V1.data(), VN.data(),
                     VX.data());
        CHECK(same(V0, W0));
        CHECK(same(V1, W1));
        CHECK(same(VN, WN));
        CHECK(same(VX, WX));
      }
    }
  }
  CHECK(cut_inside > 200);
  CHECK(cut_clamped > 200);
}
