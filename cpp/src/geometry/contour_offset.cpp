// The only translation unit that sees CGAL's 2-D polygon offsets and Boolean set operations.
#include "netshape/geometry/contour_offset.hpp"

#include <CGAL/Exact_predicates_exact_constructions_kernel.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/General_polygon_set_2.h>
#include <CGAL/Gps_circle_segment_traits_2.h>
#include <CGAL/Polygon_2.h>
#include <CGAL/approximated_offset_2.h>

#include <cmath>
#include <list>
#include <string>

#include "netshape/core/error.hpp"

namespace netshape::geometry {

namespace {
using EK = CGAL::Exact_predicates_exact_constructions_kernel;
using IK = CGAL::Exact_predicates_inexact_constructions_kernel;
using Traits = CGAL::Gps_circle_segment_traits_2<EK>;
using GPolygon = Traits::Polygon_2;
using GPwh = Traits::Polygon_with_holes_2;
using GSet = CGAL::General_polygon_set_2<Traits>;
using XCurve = Traits::X_monotone_curve_2;

double signed_area(const Points2& p) {
  double a = 0;
  for (Eigen::Index i = 0; i < p.rows(); ++i) {
    const Eigen::Index j = (i + 1) % p.rows();
    a += p(i, 0) * p(j, 1) - p(j, 0) * p(i, 1);
  }
  return 0.5 * a;
}

void check_contour(const Points2& p, const std::string& field) {
  NETSHAPE_CHECK(p.rows() >= 3, (field + ".rows").c_str(), p.rows(), "a contour needs at least 3 vertices");
  for (Eigen::Index i = 0; i < p.rows(); ++i)
    for (int c = 0; c < 2; ++c)
      NETSHAPE_CHECK(std::isfinite(p(i, c)), (field + "[" + std::to_string(i) + "]").c_str(), p(i, c),
                     "must be finite [mm]");
  CGAL::Polygon_2<IK> poly;
  for (Eigen::Index i = 0; i < p.rows(); ++i) poly.push_back(IK::Point_2(p(i, 0), p(i, 1)));
  // repeated consecutive vertices make is_simple() false too; say which
  for (Eigen::Index i = 0; i < p.rows(); ++i) {
    const Eigen::Index j = (i + 1) % p.rows();
    NETSHAPE_CHECK(p.row(i) != p.row(j), (field + "[" + std::to_string(j) + "]").c_str(), p(j, 0),
                   "repeats the previous vertex (remove duplicates; do not repeat the first at the end)");
  }
  NETSHAPE_CHECK(poly.is_simple(), field.c_str(), p.rows(),
                 "contour is self-intersecting (not a simple polygon)");
  NETSHAPE_CHECK(std::abs(signed_area(p)) > 0, field.c_str(), 0.0, "contour has zero area");
}

CGAL::Polygon_2<EK> to_exact_ccw(const Points2& p, bool ccw) {
  CGAL::Polygon_2<EK> poly;
  for (Eigen::Index i = 0; i < p.rows(); ++i) poly.push_back(EK::Point_2(p(i, 0), p(i, 1)));
  if ((poly.orientation() == CGAL::COUNTERCLOCKWISE) != ccw) poly.reverse_orientation();
  return poly;
}

// One x-monotone circle-segment curve → a Block (line or arc) at height z.
toolpath::Block to_block(const XCurve& c, double z) {
  toolpath::Block b;
  b.plane = toolpath::Plane::xy;
  b.start = Vec3(CGAL::to_double(c.source().x()), CGAL::to_double(c.source().y()), z);
  b.end = Vec3(CGAL::to_double(c.target().x()), CGAL::to_double(c.target().y()), z);
  if (c.is_linear()) {
    b.kind = toolpath::MotionKind::line;
  } else {
    b.kind = toolpath::MotionKind::arc;
    const auto& circ = c.supporting_circle();
    b.center = Vec3(CGAL::to_double(circ.center().x()), CGAL::to_double(circ.center().y()), z);
    b.clockwise = c.orientation() == CGAL::CLOCKWISE;
  }
  return b;
}

OffsetRing ring_of(const GPolygon& pg, bool hole) {
  OffsetRing r;
  r.hole = hole;
  for (auto it = pg.curves_begin(); it != pg.curves_end(); ++it) {
    toolpath::Block b = to_block(*it, 0.0);
    if ((b.end - b.start).norm() <= 1e-12 && b.kind == toolpath::MotionKind::line) continue;
    // merge consecutive pieces of the same arc (x-monotone splitting) back into one arc
    if (!r.blocks.empty() && b.kind == toolpath::MotionKind::arc && r.blocks.back().kind == toolpath::MotionKind::arc &&
        (r.blocks.back().center - b.center).norm() <= 1e-9 && r.blocks.back().clockwise == b.clockwise &&
        (r.blocks.back().end - b.start).norm() <= 1e-9) {
      const toolpath::Block& prev = r.blocks.back();
      toolpath::Block m = prev;
      m.end = b.end;
      const double sweep = std::abs(prev.sweep()) + std::abs(b.sweep());
      if (sweep < 2 * pi - 1e-9) {
        r.blocks.back() = m;
        continue;
      }
    }
    r.blocks.push_back(b);
  }
  return r;
}

void collect(const GSet& set, std::vector<OffsetRing>& out) {
  std::list<GPwh> parts;
  set.polygons_with_holes(std::back_inserter(parts));
  for (const GPwh& p : parts) {
    if (p.is_unbounded()) continue;
    GPolygon outer = p.outer_boundary();
    if (outer.orientation() != CGAL::COUNTERCLOCKWISE) outer.reverse_orientation();
    out.push_back(ring_of(outer, false));
    for (auto h = p.holes_begin(); h != p.holes_end(); ++h) {
      GPolygon hole = *h;
      if (hole.orientation() != CGAL::CLOCKWISE) hole.reverse_orientation();
      out.push_back(ring_of(hole, true));
    }
  }
}

}  // namespace

void Region::validate() const {
  check_contour(outer, "outer");
  for (std::size_t k = 0; k < islands.size(); ++k) check_contour(islands[k], "islands[" + std::to_string(k) + "]");
}

double OffsetRing::area() const {
  double a = 0.0;
  for (const auto& b : blocks) {
    a += 0.5 * (b.start.x() * b.end.y() - b.end.x() * b.start.y());
    if (b.kind == toolpath::MotionKind::arc) {
      const double r = (b.start - b.center).norm();
      const double th = b.sweep();  // signed, ccw positive
      a += 0.5 * r * r * (th - std::sin(th));
    }
  }
  return a;
}

Points2 OffsetRing::polyline(double tol) const {
  NETSHAPE_CHECK(std::isfinite(tol) && tol > 0, "chord_tolerance", tol, "must be positive [mm]");
  std::vector<Vec2> pts;
  for (const auto& b : blocks) {
    int n = 1;
    if (b.kind == toolpath::MotionKind::arc) {
      n = toolpath::chord_count(b.radius(), b.sweep(), tol);
    }
    for (int k = 0; k < n; ++k) {
      const Vec3 p = b.point_at(static_cast<double>(k) / n);
      pts.emplace_back(p.x(), p.y());
    }
  }
  Points2 out(static_cast<Eigen::Index>(pts.size()), 2);
  for (std::size_t i = 0; i < pts.size(); ++i) out.row(static_cast<Eigen::Index>(i)) = pts[i].transpose();
  return out;
}

std::vector<OffsetRing> offset_region(const Region& region, double d, double tolerance) {
  region.validate();
  NETSHAPE_CHECK(std::isfinite(d) && d != 0.0, "distance", d, "must be finite and non-zero [mm]");
  NETSHAPE_CHECK(std::isfinite(tolerance) && tolerance > 0, "tolerance", tolerance, "must be positive [mm]");
  const CGAL::Polygon_2<EK> outer = to_exact_ccw(region.outer, true);
  GSet set;
  if (d > 0) {
    // grow: outer ⊕ disk, islands shrink (inset of each island), i.e. region ⊕ disk
    set.insert(CGAL::approximated_offset_2(outer, d, tolerance));
    for (const Points2& isl : region.islands) {
      const CGAL::Polygon_2<EK> ip = to_exact_ccw(isl, true);
      std::list<GPolygon> insets;
      CGAL::approximated_inset_2(ip, d, tolerance, std::back_inserter(insets));
      // the island minus the band of width d around the region: the part still uncovered
      GSet hole;
      for (const GPolygon& h : insets) hole.join(h);
      set.difference(hole);
    }
  } else {
    const double r = -d;
    std::list<GPolygon> insets;
    CGAL::approximated_inset_2(outer, r, tolerance, std::back_inserter(insets));
    for (const GPolygon& p : insets) set.join(p);
    for (const Points2& isl : region.islands) {
      if (set.is_empty()) break;
      const CGAL::Polygon_2<EK> ip = to_exact_ccw(isl, true);
      set.difference(CGAL::approximated_offset_2(ip, r, tolerance));
    }
  }
  std::vector<OffsetRing> out;
  collect(set, out);
  return out;
}

std::vector<std::vector<OffsetRing>> pocket_rings(const Region& region, double tool_radius, double step_over,
                                                  double tolerance) {
  NETSHAPE_CHECK(std::isfinite(tool_radius) && tool_radius > 0, "tool_radius", tool_radius, "must be positive [mm]");
  NETSHAPE_CHECK(std::isfinite(step_over) && step_over > 0, "step_over", step_over, "must be positive [mm]");
  NETSHAPE_CHECK(step_over <= 2 * tool_radius, "step_over", step_over, "must not exceed the tool diameter [mm]");
  region.validate();
  std::vector<std::vector<OffsetRing>> levels;
  for (int k = 0; k < 100000; ++k) {
    auto rings = offset_region(region, -(tool_radius + k * step_over), tolerance);
    if (rings.empty()) break;
    levels.push_back(std::move(rings));
  }
  return levels;
}

toolpath::Toolpath rings_toolpath(const std::vector<std::vector<OffsetRing>>& levels, double z, double clearance,
                                  double feed, double spindle_rpm, int tool) {
  NETSHAPE_CHECK_FINITE("z", z);
  NETSHAPE_CHECK(std::isfinite(clearance) && clearance > 0, "clearance", clearance, "must be positive [mm]");
  NETSHAPE_CHECK(std::isfinite(feed) && feed > 0, "feed", feed, "must be positive [mm/s]");
  toolpath::Toolpath tp;
  tp.source = "pocket";
  Vec3 at;
  bool have = false;
  auto push = [&](toolpath::Block b) {
    b.feed = feed;
    b.spindle_rpm = spindle_rpm;
    b.tool = tool;
    tp.blocks.push_back(b);
  };
  const Vec3 up(0, 0, clearance);
  for (auto lv = levels.rbegin(); lv != levels.rend(); ++lv) {
    for (const OffsetRing& ring : *lv) {
      if (ring.blocks.empty()) continue;
      const Vec3 s(ring.blocks.front().start.x(), ring.blocks.front().start.y(), z);
      toolpath::Block r;
      r.kind = toolpath::MotionKind::rapid;
      if (have) {
        r.start = at;
        r.end = at + up;
        push(r);
        r.start = at + up;
      } else {
        r.start = s + up + up;
      }
      r.end = s + up;
      if ((r.end - r.start).norm() > 0) push(r);
      toolpath::Block pl;
      pl.kind = toolpath::MotionKind::line;
      pl.start = s + up;
      pl.end = s;
      push(pl);
      for (toolpath::Block b : ring.blocks) {
        b.start.z() = z;
        b.end.z() = z;
        b.center.z() = z;
        push(b);
      }
      at = Vec3(ring.blocks.back().end.x(), ring.blocks.back().end.y(), z);
      have = true;
    }
  }
  if (have) {
    toolpath::Block r;
    r.kind = toolpath::MotionKind::rapid;
    r.start = at;
    r.end = at + up;
    push(r);
  }
  return tp;
}

}  // namespace netshape::geometry
