// deviation_to_program() (netshape/motion/smoothing.hpp): samples of a smoothed path against the
// program blocks they replace.
#include <algorithm>
#include <cmath>
#include <vector>

#include "netshape/core/error.hpp"
#include "netshape/motion/segment.hpp"
#include "netshape/motion/smoothing.hpp"

namespace netshape::motion {

namespace {

/// Exact distance from p to a circular arc of constant radius in its plane (no helical travel, no
/// spiral); false for other arcs, which the caller measures along a polyline.
bool circular_arc_distance(const toolpath::Block& b, const Vec3& p, double& out) {
  const toolpath::PlaneAxes ax = toolpath::plane_axes(b.plane);
  const double r = b.radius();
  const double r1 = std::hypot(b.end[ax.a] - b.center[ax.a], b.end[ax.b] - b.center[ax.b]);
  const double eps = 1e-12 * (1.0 + r);
  if (std::abs(b.end[ax.n] - b.start[ax.n]) > eps || std::abs(r1 - r) > eps) return false;
  const double du = p[ax.a] - b.center[ax.a], dv = p[ax.b] - b.center[ax.b], dn = p[ax.n] - b.start[ax.n];
  const double rho = std::hypot(du, dv);
  const double sweep = b.sweep();
  bool inside = std::abs(sweep) >= 2.0 * pi || rho == 0.0;
  if (!inside) {
    const double a0 = std::atan2(b.start[ax.b] - b.center[ax.b], b.start[ax.a] - b.center[ax.a]);
    double rel = (std::atan2(dv, du) - a0) * (sweep < 0 ? -1.0 : 1.0);
    rel -= 2.0 * pi * std::floor(rel / (2.0 * pi));  // [0, 2π)
    inside = rel <= std::abs(sweep);
  }
  out = inside ? std::hypot(rho - r, dn) : std::min((p - b.start).norm(), (p - b.end).norm());
  return true;
}

}  // namespace

double deviation_to_program(const std::vector<toolpath::Block>& program, const Points3& points,
                            const std::vector<long>& first, const std::vector<long>& last) {
  NETSHAPE_CHECK(static_cast<Eigen::Index>(first.size()) == points.rows() && first.size() == last.size(), "first",
                 first.size(), "must have one entry per point (and match last)");
  const long nb = static_cast<long>(program.size());
  double dev = 0;
  std::vector<Segment> segs;
  segs.reserve(program.size());
  for (const auto& b : program)
    segs.push_back(b.kind == toolpath::MotionKind::arc ? Segment::arc(b, 0) : Segment::line(b, 0));
  for (Eigen::Index k = 0; k < points.rows(); ++k) {
    const Vec3 p = points.row(k).transpose();
    const auto kk = static_cast<std::size_t>(k);
    double best = 1e300;
    for (long q = std::max(0L, first[kk] - 1); q <= std::min(nb - 1, last[kk] + 1); ++q) {
      const Segment& s = segs[static_cast<std::size_t>(q)];
      if (s.full_length <= 0) continue;
      double d;
      if (s.kind != SegmentKind::arc || !circular_arc_distance(s.block, p, d))
        d = s.distance_to_piece(p, 0.0, s.full_length);
      best = std::min(best, d);
    }
    if (best < 1e300) dev = std::max(dev, best);
  }
  return dev;
}

}  // namespace netshape::motion
