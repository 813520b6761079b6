#include "netshape/motion/segment.hpp"

#include <algorithm>
#include <cmath>

namespace netshape::motion {

Vec3 bezier_point(const std::array<Vec3, 4>& c, double u) noexcept {
  const double v = 1.0 - u;
  return v * v * v * c[0] + 3 * v * v * u * c[1] + 3 * v * u * u * c[2] + u * u * u * c[3];
}
Vec3 bezier_d1(const std::array<Vec3, 4>& c, double u) noexcept {
  const double v = 1.0 - u;
  return 3 * v * v * (c[1] - c[0]) + 6 * v * u * (c[2] - c[1]) + 3 * u * u * (c[3] - c[2]);
}
Vec3 bezier_d2(const std::array<Vec3, 4>& c, double u) noexcept {
  return 6 * (1.0 - u) * (c[2] - 2 * c[1] + c[0]) + 6 * u * (c[3] - 2 * c[2] + c[1]);
}

namespace {
// 5-point Gauss-Legendre nodes and weights on [−1, 1]
constexpr double gauss5_x[5] = {0.0, -0.5384693101056831, 0.5384693101056831, -0.9061798459386640,
                                0.9061798459386640};
constexpr double gauss5_w[5] = {0.5688888888888889, 0.4786286704993665, 0.4786286704993665,
                                0.2369268850561891, 0.2369268850561891};

// The hodograph as a polynomial, B'(u) = c0 + c1·u + c2·u² (B''(u) = c1 + 2·c2·u), and whether the
// Bézier is a blend between two lines (P1 = P2, |P1 − P0| = |P3 − P2|), symmetric about u = 1/2.
struct Hodograph {
  Vec3 c0, c1, c2;
  bool symmetric;
  explicit Hodograph(const std::array<Vec3, 4>& c) noexcept {
    const Vec3 d0 = c[1] - c[0], d1 = c[2] - c[1], d2 = c[3] - c[2];
    c0 = 3.0 * d0;
    c1 = 6.0 * (d1 - d0);
    c2 = 3.0 * (d0 - 2.0 * d1 + d2);
    const double n0 = d0.squaredNorm();
    symmetric = d1.squaredNorm() <= 1e-20 * n0 && std::abs(n0 - d2.squaredNorm()) <= 1e-12 * n0;
  }
};

// Unit tangent v1/|v1|, curvature vector (the normal part of B'' over |B'|²) and curvature k_at at the
// table nodes u = i/16; on a symmetric blend |B'| and κ at node 16 − i equal those at node i.
void node_frames(const Hodograph& g, double (&k_at)[17], std::array<Vec3, 17>* tangent,
                 std::array<Vec3, 17>* curvature_vector) noexcept {
  const Vec3 &c0 = g.c0, &c1 = g.c1, &c2 = g.c2;
  const bool symmetric = g.symmetric;
  double isp_at[17];
  for (int i = 0; i <= 16; ++i) {
    const double u = i / 16.0;
    const Vec3 v1 = c0 + u * (c1 + u * c2), v2 = c1 + 2.0 * u * c2;
    const double sp2 = v1.squaredNorm();
    Vec3 tn = Vec3::Zero(), kv = Vec3::Zero();
    double k = 0.0;
    if (sp2 > 0) {
      const double isp = symmetric && i > 8 ? isp_at[16 - i] : 1.0 / std::sqrt(sp2);
      const double isp2 = isp * isp;
      kv = (v2 - (v2.dot(v1) * isp2) * v1) * isp2;
      tn = v1 * isp;
      isp_at[i] = isp;
      k = symmetric && i > 8 ? k_at[16 - i] : kv.norm();
    } else {
      isp_at[i] = 0.0;
    }
    k_at[i] = k;
    if (tangent) (*tangent)[static_cast<std::size_t>(i)] = tn;
    if (curvature_vector) (*curvature_vector)[static_cast<std::size_t>(i)] = kv;
  }
}

}  // namespace

Segment Segment::line(const toolpath::Block& b, long source) {
  Segment s;
  s.kind = SegmentKind::line;
  s.block = b;
  s.full_length = (b.end - b.start).norm();
  s.source = source;
  return s;
}

Segment Segment::arc(const toolpath::Block& b, long source) {
  Segment s;
  s.kind = SegmentKind::arc;
  s.block = b;
  s.full_length = b.length();
  s.curvature = b.curvature();
  s.source = source;
  return s;
}

Segment Segment::blend(const Vec3& p0, const Vec3& p1, const Vec3& p2, const Vec3& p3, long source,
                       std::array<Vec3, 17>* tangent, std::array<Vec3, 17>* curvature_vector) {
  Segment s;
  s.kind = SegmentKind::blend;
  s.ctrl = {p0, p1, p2, p3};
  s.source = source;
  const Hodograph g(s.ctrl);
  // |B'(u)|² as a quartic
  const Vec3 &c0 = g.c0, &c1 = g.c1, &c2 = g.c2;
  const double q0 = c0.squaredNorm(), q1 = 2.0 * c0.dot(c1), q2 = c1.squaredNorm() + 2.0 * c0.dot(c2),
               q3 = 2.0 * c1.dot(c2), q4 = c2.squaredNorm();
  auto speed = [&](double u) { return std::sqrt(std::max(0.0, q0 + u * (q1 + u * (q2 + u * (q3 + u * q4))))); };
  // arc-length table at u = i/16 (3-point Gauss-Legendre per interval, exact to ~1e-9 relative for
  // these smooth speeds) and curvature at the same nodes; |dκ/ds| from neighbouring nodes.
  // A symmetric blend's second half of the intervals mirrors the first.
  static const double gx = 0.7745966692414834, w0 = 8.0 / 9.0, w1 = 5.0 / 9.0;
  double piece[16];
  const int n_eval = g.symmetric ? 8 : 16;
  for (int i = 0; i < n_eval; ++i) {
    const double m = (i + 0.5) / 16.0, h = 0.5 / 16.0;
    piece[i] = h * (w0 * speed(m) + w1 * (speed(m - h * gx) + speed(m + h * gx)));
  }
  if (g.symmetric)
    for (int i = 0; i < 8; ++i) piece[15 - i] = piece[i];
  s.table[0] = 0;
  for (int i = 1; i <= 16; ++i) s.table[i] = s.table[i - 1] + piece[i - 1];
  double k_at[17];
  node_frames(g, k_at, tangent, curvature_vector);
  finish_blend(s, k_at, g.symmetric);
  return s;
}

void bezier_node_frames(const std::array<Vec3, 4>& c, std::array<Vec3, 17>& tangent,
                        std::array<Vec3, 17>& curvature_vector) noexcept {
  double k_at[17];
  node_frames(Hodograph(c), k_at, &tangent, &curvature_vector);
}

void finish_blend(Segment& s, const double (&k_at)[17], bool symmetric) noexcept {
  // largest curvature and |dκ/ds| between neighbouring nodes, as arrays (Eigen vectorises the
  // divisions); the largest quotient is the quotient of the largest fraction, since rounding is
  // monotone. A symmetric blend's second half mirrors its first: nodes 0..8 and intervals 0..7 suffice.
  const Eigen::Map<const Eigen::Array<double, 17, 1>> k(k_at), t(s.table.data());
  const int n = symmetric ? 8 : 16;
  using A = Eigen::Array<double, Eigen::Dynamic, 1, 0, 16, 1>;  // at most 16, no allocation
  const A dk = (k.segment(1, n) - k.head(n)).abs(), ds = t.segment(1, n) - t.head(n);
  s.curvature = k.head(n + 1).maxCoeff();
  s.curvature_rate = (ds > 0).select(dk / (ds > 0).select(ds, 1.0), 0.0).maxCoeff();
  s.full_length = s.table[16];
}

double Segment::bezier_u(double s) const noexcept {
  if (s <= 0) return 0.0;
  if (s >= full_length) return 1.0;
  int i = static_cast<int>(std::upper_bound(table.begin(), table.end(), s) - table.begin()) - 1;
  i = std::clamp(i, 0, 15);
  const double l0 = table[i], l1 = table[i + 1], ua = i / 16.0, ub = (i + 1) / 16.0;
  const Hodograph g(ctrl);
  const Vec3 &c0 = g.c0, &c1 = g.c1, &c2 = g.c2;
  auto hodograph = [&](double u) { return Vec3(c0 + u * (c1 + u * c2)); };
  // first guess: the quintic Hermite interpolant of u(s) on [l0, l1] from u, du/ds = 1/|B'| and
  // d²u/ds² = −(d|B'|/du)/|B'|³ at the two table nodes (error O(h⁶) in the interval width); the linear
  // interpolant where a node speed vanishes
  const double h = l1 - l0, t = h > 0 ? (s - l0) / h : 0.0;
  double u = ua + t / 16.0;
  const Vec3 va = hodograph(ua), vb = hodograph(ub);
  const double qa = va.squaredNorm(), qb = vb.squaredNorm();
  if (h > 0 && qa > 0 && qb > 0) {
    const double ia = 1.0 / std::sqrt(qa), ib = 1.0 / std::sqrt(qb);
    // derivatives in t = (s − l0)/h: u_t = h/|B'|, u_tt = −h²·(B'·B'')/|B'|⁴
    const double ma = h * ia, mb = h * ib;
    const double aa = -h * h * va.dot(c1 + 2.0 * ua * c2) * (ia * ia) * (ia * ia);
    const double ab = -h * h * vb.dot(c1 + 2.0 * ub * c2) * (ib * ib) * (ib * ib);
    const double t2 = t * t, t3 = t2 * t, t4 = t3 * t, t5 = t4 * t;
    const double h5 = 10 * t3 - 15 * t4 + 6 * t5;  // the basis of the end value (the start's is 1 − h5)
    u = ua + (ub - ua) * h5 + ma * (t - 6 * t3 + 8 * t4 - 3 * t5) + mb * (-4 * t3 + 7 * t4 - 3 * t5) +
        aa * 0.5 * (t2 - 3 * t3 + 3 * t4 - t5) + ab * 0.5 * (t3 - 2 * t4 + t5);
    u = std::clamp(u, ua, ub);
  }
  // Newton on l0 + ∫_{ua}^{u} |B'| − s (5-point Gauss); the error after a step δ is about
  // |d|B'|/du| / (2|B'|)·δ², so the steps stop once that is below 1e-17 (under half an ulp of u ≤ 1)
  for (int it = 0; it < 8; ++it) {
    // 5-point Gauss-Legendre of |B'| on [ua, u]
    const double hh = 0.5 * (u - ua), m = 0.5 * (ua + u);
    double len = gauss5_w[0] * hodograph(m).norm();
    for (int q = 1; q < 5; ++q) len += gauss5_w[q] * hodograph(m + hh * gauss5_x[q]).norm();
    const double f = l0 + len * hh - s;
    const Vec3 v1 = hodograph(u);
    const double sp2 = v1.squaredNorm();
    if (!(sp2 > 0)) break;
    const double sp = std::sqrt(sp2);
    const double rate = std::abs(v1.dot(c1 + 2.0 * u * c2)) / sp2;  // |d|B'|/du| / |B'|
    const double next = std::clamp(u - f / sp, ua, ub), du = next - u;
    u = next;
    if (0.5 * rate * du * du <= 1e-17) break;
  }
  return u;
}

Vec3 Segment::point_at(double s) const noexcept {
  switch (kind) {
    case SegmentKind::line: {
      if (full_length <= 0) return block.start;
      const double f = (trim_start + s) / full_length;
      if (f >= 1.0) return block.end;
      return block.start + f * (block.end - block.start);
    }
    case SegmentKind::arc: return block.point_at(std::clamp((trim_start + s) / full_length, 0.0, 1.0));
    case SegmentKind::blend: return bezier_point(ctrl, bezier_u(trim_start + s));
  }
  return Vec3::Zero();
}

Vec3 Segment::tangent_at(double s) const noexcept {
  switch (kind) {
    case SegmentKind::line: return block.tangent_at(0.0);
    case SegmentKind::arc: return block.tangent_at(std::clamp((trim_start + s) / full_length, 0.0, 1.0));
    case SegmentKind::blend: {
      const Vec3 d = bezier_d1(ctrl, bezier_u(trim_start + s));
      const double n = d.norm();
      return n > 0 ? Vec3(d / n) : Vec3((ctrl[3] - ctrl[0]).normalized());
    }
  }
  return Vec3::Zero();
}

Vec3 Segment::moving_axes() const noexcept {
  Vec3 m = Vec3::Zero();
  auto mark = [&m](const Vec3& d) {
    for (int i = 0; i < 3; ++i)
      if (std::abs(d[i]) > 1e-12) m[i] = 1.0;
  };
  switch (kind) {
    case SegmentKind::line: mark(block.end - block.start); break;
    case SegmentKind::arc: {
      const auto ax = toolpath::plane_axes(block.plane);
      m[ax.a] = m[ax.b] = 1.0;
      if (std::abs(block.end[ax.n] - block.start[ax.n]) > 1e-12) m[ax.n] = 1.0;
      break;
    }
    case SegmentKind::blend:
      mark(ctrl[1] - ctrl[0]);
      mark(ctrl[2] - ctrl[1]);
      mark(ctrl[3] - ctrl[2]);
      break;
  }
  return m;
}

namespace {
constexpr int polyline_chords = 64;  // distance_to_piece: chords per pass
}  // namespace

void Segment::piece_polyline(double s0, double s1, PiecePolyline& out) const noexcept {
  s0 = std::clamp(s0, 0.0, full_length);
  s1 = std::clamp(s1, s0, full_length);
  for (int i = 0; i <= polyline_chords; ++i) {
    const double s = i == 0 ? s0 : s0 + (s1 - s0) * i / polyline_chords;
    out[static_cast<std::size_t>(i)] = kind == SegmentKind::arc ? block.point_at(s / full_length) : bezier_point(ctrl, bezier_u(s));
  }
}

double Segment::distance_to_piece(const Vec3& p, double s0, double s1, const PiecePolyline* coarse,
                                  double enough) const noexcept {
  s0 = std::clamp(s0, 0.0, full_length);
  s1 = std::clamp(s1, s0, full_length);
  if (kind == SegmentKind::line) {
    const Vec3 a = block.start + (full_length > 0 ? s0 / full_length : 0.0) * (block.end - block.start);
    const Vec3 b = block.start + (full_length > 0 ? s1 / full_length : 0.0) * (block.end - block.start);
    return point_segment_distance(p, a, b);
  }
  // arcs (and blends): a fine polyline; refine around the nearest vertex
  constexpr int n = polyline_chords;
  auto at = [&](double s) {
    return kind == SegmentKind::arc ? block.point_at(s / full_length) : bezier_point(ctrl, bezier_u(s));
  };
  PiecePolyline own;
  if (!coarse) {
    piece_polyline(s0, s1, own);
    coarse = &own;
  }
  const PiecePolyline& q = *coarse;
  double best = 1e300, sb = s0;
  for (int i = 1; i <= n; ++i) {
    const double d = point_segment_distance(p, q[static_cast<std::size_t>(i - 1)], q[static_cast<std::size_t>(i)]);
    if (d < best) {
      best = d;
      sb = s0 + (s1 - s0) * i / n;
      if (best <= enough) return best;  // (the smallest distance is at most this one)
    }
  }
  // second, finer pass on the best chord pair
  const double h = (s1 - s0) / n;
  const double a = std::max(s0, sb - 2 * h), b = std::min(s1, sb + h);
  Vec3 prev = at(a);
  for (int i = 1; i <= n; ++i) {
    const double s = a + (b - a) * i / n;
    const Vec3 next = at(s);
    best = std::min(best, point_segment_distance(p, prev, next));
    if (best <= enough) return best;
    prev = next;
  }
  return best;
}

}  // namespace netshape::motion
