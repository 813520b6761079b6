#pragma once
// The tolerance-band smoothing stage's compound corners (private, included by smoothing.cpp only, so
// everything here has internal linkage): one tangent arc for a corner made of several vertices a few
// micrometres apart, checked both ways against the polyline it replaces.
#include <algorithm>
#include <cmath>
#include <vector>

#include "motion/smoothing/spline.hpp"

namespace netshape::motion {
namespace {

// The arc inside a sharp corner turning th whose distance from the vertex is e: for the half interior
// angle φ = (π − th)/2 its radius is e·sin φ / (1 − sin φ), and it touches each line R·tan(th/2) from the
// vertex.
inline double corner_arc_radius(double th, double e) {
  const double sphi = std::cos(0.5 * th);
  return e * sphi / (1.0 - sphi);
}

// A tangent arc from p1 on line 1 to p2 on line 2 (center c, radius r, turning counter-clockwise when
// ccw).
struct CornerArc {
  V2 p1, p2, c;
  double r = 0;
  bool ccw = true;
};

// Largest distance between the arc of `a` (turn th) and the polyline q (q.front() = a.p1,
// q.back() = a.p2), both ways, as an upper bound.
//   polyline -> arc: every vertex of q lies in the wedge of the arc (between the radii to p1 and p2;
//   else the bound is infinite), so the distance of a point x of q to the arc is |‖x − c‖ − r|; along
//   a segment ‖x − c‖ is convex, so its largest value is at an end and its smallest at the foot of c.
//   arc -> polyline: chords of the arc with sagitta σ; a chord's points are within
//   max(d(c0, S), d(c1, S)) + σ of segment S (the distance to a segment is convex).
// Returns as soon as the bound exceeds `limit` (a value above it then).
inline double corner_arc_gap(const CornerArc& a, double th, const std::vector<V2>& q, double chord, double limit) {
  const V2 u1 = a.p1 - a.c, u2 = a.p2 - a.c;
  const double sg = a.ccw ? 1.0 : -1.0;
  const double slack = 1e-12 * (1.0 + a.r);
  double gap = 0;
  for (const V2& x : q) {
    const V2 v = x - a.c;
    if (sg * cross2(u1, v) < -slack || sg * cross2(v, u2) < -slack) return 1e300;
  }
  std::vector<Seg> segs;
  segs.reserve(q.size());
  for (std::size_t i = 0; i + 1 < q.size(); ++i) {
    segs.push_back(make_seg(q[i], q[i + 1]));
    const double far = std::max((q[i] - a.c).norm(), (q[i + 1] - a.c).norm());
    const double near = std::sqrt(dist2(a.c, segs.back()));
    gap = std::max({gap, far - a.r, a.r - near});
  }
  if (gap > limit) return gap;
  const int n = std::clamp(static_cast<int>(std::ceil(th * a.r / chord)), 4, 1024);
  const double step = th / n;
  const double sag = a.r * (1.0 - std::cos(0.5 * step));
  V2 c0 = a.p1;
  for (int k = 1; k <= n; ++k) {
    const double ang = sg * step * k;
    const V2 c1 = k == n ? a.p2 : V2(a.c + V2(std::cos(ang) * u1.x() - std::sin(ang) * u1.y(),
                                               std::sin(ang) * u1.x() + std::cos(ang) * u1.y()));
    double best = 1e300;
    for (const Seg& sg : segs) best = std::min(best, std::max(dist2(c0, sg), dist2(c1, sg)));
    gap = std::max(gap, std::sqrt(best) + sag);
    if (gap > limit) return gap;
    c0 = c1;
  }
  return gap;
}

// One arc for the corner between line 1 (direction d1, ending at the first vertex of `mid`) and line 2
// (direction d2, starting at the last vertex of `mid`), with the vertices in between (`mid`: the
// polyline from the end of line 1 to the start of line 2, at least two points). The arc is tangent
// to both lines at equal distances T from their intersection X; its ends may lie at most cap1 before
// the end of line 1 and cap2 after the start of line 2. The largest T whose arc is within e of the
// polyline it replaces (the lines' cut-off pieces and `mid`), both ways, wins. False when the lines
// are (nearly) parallel, X is undefined, or no T in range keeps within e.
inline bool compound_corner_arc(const std::vector<V2>& mid, const V2& d1, const V2& d2, double cap1, double cap2,
                         double e, CornerArc& out) {
  const V2 A = mid.front(), B = mid.back();
  const double den = cross2(d1, d2);
  const double th = std::atan2(std::abs(den), d1.dot(d2));
  if (th < 1e-3 || th > 3.0) return false;
  // X = A + s·d1 = B − t·d2
  const V2 w = B - A;
  const double s = cross2(w, d2) / den, t = cross2(d1, w) / den;
  const V2 X = A + s * d1;
  const double lo = std::max({s, t, 0.0}), hi = std::min(s + cap1, t + cap2);
  if (!(hi > lo)) return false;
  const bool ccw = den > 0;
  const double tan_half = std::tan(0.5 * th);
  const double chord = 0.05 * e;
  std::vector<V2> q;
  auto gap_at = [&](double T, CornerArc& a) {
    a.p1 = X - T * d1;
    a.p2 = X + T * d2;
    a.r = T / tan_half;
    a.ccw = ccw;
    a.c = a.p1 + a.r * (ccw ? perp(d1) : V2(-perp(d1)));
    q.assign(1, a.p1);
    q.insert(q.end(), mid.begin(), mid.end());
    q.push_back(a.p2);
    return corner_arc_gap(a, th, q, chord, e);
  };
  CornerArc a;
  if (gap_at(hi, a) <= e) {
    out = a;
    return true;
  }
  // the largest passing T on a grid from hi down to lo, then bisection towards the failing one above
  constexpr int grid = 12;
  double fail = hi, pass = -1;
  for (int k = grid - 1; k >= 0; --k) {
    const double T = lo + (hi - lo) * k / grid;
    if (T <= 0) break;
    if (gap_at(T, a) <= e) {
      pass = T;
      out = a;
      break;
    }
    fail = T;
  }
  if (pass < 0) return false;
  for (int it = 0; it < 6; ++it) {
    const double T = 0.5 * (pass + fail);
    if (gap_at(T, a) <= e) {
      pass = T;
      out = a;
    } else {
      fail = T;
    }
  }
  return true;
}

}  // namespace
}  // namespace netshape::motion
