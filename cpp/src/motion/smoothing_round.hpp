#pragma once
// The tolerance-band smoothing stage's corners between program lines (private, included by
// smoothing.cpp only, so everything here has internal linkage).
#include <algorithm>
#include <cmath>
#include <vector>

#include "netshape/motion/smoothing.hpp"
#include "netshape/toolpath/block.hpp"
#include "smoothing_corner.hpp"
#include "smoothing_fit.hpp"

namespace netshape::motion {
namespace {

// Corners between two program lines (kept corners, the vertices of runs left as programmed, joints
// of long lines): a tangent arc inside the corner whose distance from the vertex is the fit tolerance
// e, so the planner no longer has to turn there within the blend tolerance. For a turn θ (half
// interior angle φ = (π − θ)/2) the arc has radius R = e·sin φ / (1 − sin φ) and touches the lines at
// T = R·tan(θ/2) from the vertex; T is capped at half of each line's length before rounding, or at
// 0.95 of it when its other end joins a curve tangentially (no arc there); R and the vertex distance
// shrink with it. Every point of the arc and of the two cut-off line pieces is then within e of the
// other. A corner made of several vertices (up to four program lines shorter than lead_min between
// two longer lines: CAM output often turns a corner over a few micrometre-long blocks) gets one arc
// tangent to the two longer lines, the largest whose distance from the replaced polyline is at
// most e both ways (compound_corner_arc); where none is, its vertices are rounded one by one.
// program_line: per block of res, a program line or a part of one; tangent_join: per block, bit 0 its
// start, bit 1 its end joins a run's curve tangentially; lead_min: the shortest line that closes a
// compound corner [mm].
void round_line_corners(SmoothResult& res, const std::vector<bool>& program_line,
                        const std::vector<unsigned char>& tangent_join, double lead_min, const SmoothOptions& opt) {
  using toolpath::MotionKind;
  const double e = opt.fit_tolerance();
  const std::size_t nr = res.blocks.size();
  std::vector<double> len0(nr);
  for (std::size_t k = 0; k < nr; ++k) len0[k] = res.blocks[k].length();
  // a line may give an arc half of itself, or nearly all when its other end joins a curve tangentially
  auto cap_end = [&](std::size_t k) { return (tangent_join[k] & 1) ? 0.95 * len0[k] : 0.5 * len0[k]; };
  auto cap_start = [&](std::size_t k) { return (tangent_join[k] & 2) ? 0.95 * len0[k] : 0.5 * len0[k]; };
  auto joined = [&](std::size_t k) {  // blocks k and k + 1: program lines, one feed, end to start
    return k + 1 < nr && program_line[k] && program_line[k + 1] && res.blocks[k].feed == res.blocks[k + 1].feed &&
           (res.blocks[k + 1].start - res.blocks[k].end).norm() <= 1e-9;
  };
  // a coordinate plane holding the points p3 (normal Z, then Y, then X); false when none does
  auto plane_of = [&](const std::vector<Vec3>& p3, toolpath::Plane& plane) {
    for (int a : {2, 1, 0}) {
      bool in = true;
      for (const Vec3& v : p3) in = in && std::abs(v[a] - p3.front()[a]) <= opt.plane_tolerance;
      if (in) {
        plane = a == 2 ? toolpath::Plane::xy : a == 1 ? toolpath::Plane::zx : toolpath::Plane::yz;
        return true;
      }
    }
    return false;
  };
  SmoothResult out;
  out.blocks.reserve(nr);
  // the arc from p1 to p2 about c2 (in the plane's coordinates), replacing the vertices between res
  // blocks first and last; it takes the feed and the rest of its fields from `like`
  auto emit_arc = [&](const toolpath::Block& like, toolpath::Plane plane, const Vec3& p1, const Vec3& p2,
                      const V2& c2, bool ccw, std::size_t first, std::size_t last) {
    const auto ax = toolpath::plane_axes(plane);
    toolpath::Block arc = like;
    arc.kind = MotionKind::arc;
    arc.plane = plane;
    arc.start = p1;
    arc.end = p2;
    arc.center = p1;
    arc.center[ax.a] = c2.x();
    arc.center[ax.b] = c2.y();
    arc.clockwise = !ccw;
    arc.turns = 1;
    out.blocks.push_back(arc);
    out.controls.emplace_back();
    out.source_first.push_back(res.source_first[first]);
    out.source_last.push_back(res.source_last[last]);
    ++out.corners_rounded;
  };
  auto emit = [&](std::size_t k) {
    out.blocks.push_back(res.blocks[k]);
    out.controls.push_back(res.controls[k]);
    out.source_first.push_back(res.source_first[k]);
    out.source_last.push_back(res.source_last[k]);
  };
  std::vector<Vec3> p3;
  std::vector<V2> mid;
  for (std::size_t k = 0; k < nr; ++k) {
    emit(k);
    if (!joined(k)) continue;
    toolpath::Block& b1 = out.blocks.back();
    const double l1 = b1.length();
    if (l1 <= 1e-9) continue;
    const Vec3 d1 = (b1.end - b1.start) / l1;
    // compound corner: lines k + 1 .. m − 1 shorter than lead_min, line m not
    std::size_t m = k + 1;
    // (a line joined to a curve at its far end is a corner's line, whatever its length)
    auto closes = [&](std::size_t q) { return len0[q] >= lead_min || (tangent_join[q] & 2); };
    while (m < k + 5 && !closes(m) && joined(m)) ++m;
    if (m > k + 1 && closes(m)) {
      p3.assign({b1.start, b1.end});
      for (std::size_t q = k + 1; q <= m; ++q) p3.push_back(res.blocks[q].end);
      toolpath::Plane plane;
      const double l2 = res.blocks[m].length();
      if (plane_of(p3, plane) && l2 > 1e-9) {
        const auto ax = toolpath::plane_axes(plane);
        auto to2 = [&](const Vec3& v) { return V2(v[ax.a], v[ax.b]); };
        const Vec3 d2 = (res.blocks[m].end - res.blocks[m].start) / l2;
        mid.assign(1, to2(b1.end));
        for (std::size_t q = k + 1; q < m; ++q) mid.push_back(to2(res.blocks[q].end));
        const double cap1 = std::min(cap_end(k), l1 - 1e-9), cap2 = std::min(cap_start(m), l2 - 1e-9);
        CornerArc ca;
        if (compound_corner_arc(mid, to2(d1), to2(d2), cap1, cap2, e, ca)) {
          // the tangent points on the lines themselves (their normal coordinate as on the lines)
          const Vec3 q1 = b1.end + (ca.p1 - to2(b1.end)).dot(to2(d1)) * d1;
          const Vec3 q2 = res.blocks[m].start + (ca.p2 - to2(res.blocks[m].start)).dot(to2(d2)) * d2;
          b1.end = q1;
          res.blocks[m].start = q2;
          emit_arc(res.blocks[m], plane, q1, q2, ca.c, ca.ccw, k, m);
          k = m - 1;  // block m is emitted next
          continue;
        }
      }
    }
    const toolpath::Block& b2 = res.blocks[k + 1];
    const double l2 = b2.length();
    if (l2 <= 1e-9) continue;
    const Vec3 d2 = (b2.end - b2.start) / l2;
    const double th = turn_between(d1, d2);
    if (th < 1e-3 || th > pi - 1e-3) continue;  // nearly straight: the planner blends it; reversals stay
    p3.assign({b1.start, b1.end, b2.end});
    toolpath::Plane plane;
    if (!plane_of(p3, plane)) continue;
    const auto ax = toolpath::plane_axes(plane);
    const double tan_half = std::tan(0.5 * th);
    double R = corner_arc_radius(th, e);
    double T = R * tan_half;
    const double cap = std::min({cap_end(k), cap_start(k + 1), l1 - 1e-9, l2 - 1e-9});
    if (T > cap) {
      T = cap;
      R = T / tan_half;
    }
    if (!(T > 1e-9)) continue;
    const Vec3 V = b1.end;
    const Vec3 p1 = V - T * d1, p2 = V + T * d2;
    const V2 t1(d1[ax.a], d1[ax.b]), t2(d2[ax.a], d2[ax.b]);
    const bool ccw = cross2(t1, t2) > 0;
    const V2 c2 = V2(p1[ax.a], p1[ax.b]) + R * (ccw ? perp(t1) : V2(-perp(t1)));
    b1.end = p1;
    res.blocks[k + 1].start = p2;
    emit_arc(b2, plane, p1, p2, c2, ccw, k, k + 1);
  }
  res.blocks = std::move(out.blocks);
  res.controls = std::move(out.controls);
  res.source_first = std::move(out.source_first);
  res.source_last = std::move(out.source_last);
  res.corners_rounded = out.corners_rounded;
}

}  // namespace
}  // namespace netshape::motion
