#include "netshape/geometry/raster.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include "netshape/core/error.hpp"
#include "netshape/geometry/cutter_location.hpp"

namespace netshape::geometry {

void RasterOptions::validate() const {
  cutter.validate();
  for (int i = 0; i < 3; ++i) NETSHAPE_CHECK_FINITE("axis", axis[i]);
  NETSHAPE_CHECK(axis.norm() > 0, "axis", axis.norm(), "tool axis must be non-zero");
  NETSHAPE_CHECK_FINITE("step_over", step_over);
  NETSHAPE_CHECK(step_over >= 0, "step_over", step_over, "must be >= 0 [mm] (0 = from the scallop height)");
  if (step_over == 0.0) {
    NETSHAPE_CHECK(std::isfinite(scallop_height) && scallop_height > 0, "scallop_height", scallop_height,
                   "must be positive [mm]");
    NETSHAPE_CHECK(cutter.kind != cutter::CutterKind::flat, "step_over", step_over,
                   "a flat end mill leaves no defined scallop: give step_over > 0 [mm]");
    NETSHAPE_CHECK(scallop_height < cutter.corner_radius, "scallop_height", scallop_height,
                   "must be less than the (corner) radius [mm]");
  }
  NETSHAPE_CHECK(std::isfinite(chord_tolerance) && chord_tolerance > 0, "chord_tolerance", chord_tolerance,
                 "must be positive [mm]");
  NETSHAPE_CHECK_FINITE("stock_allowance", stock_allowance);
  NETSHAPE_CHECK(std::isfinite(feed) && feed > 0, "feed", feed, "must be positive [mm/s]");
  NETSHAPE_CHECK(std::isfinite(plunge_feed) && plunge_feed >= 0, "plunge_feed", plunge_feed, "must be >= 0 [mm/s]");
  NETSHAPE_CHECK(std::isfinite(clearance) && clearance >= 0, "clearance", clearance, "must be >= 0 [mm]");
  NETSHAPE_CHECK_FINITE("spindle_rpm", spindle_rpm);
}

double scallop_step(double R, double h, double curvature) {
  NETSHAPE_CHECK(std::isfinite(R) && R > 0, "radius", R, "must be positive [mm]");
  NETSHAPE_CHECK(std::isfinite(h) && h > 0 && h < R, "scallop_height", h, "must be in (0, radius) [mm]");
  NETSHAPE_CHECK_FINITE("curvature", curvature);
  const double flat = 2.0 * std::sqrt(h * (2.0 * R - h));
  if (std::abs(curvature) * R < 1e-9) return flat;
  const double rho = 1.0 / curvature;  // signed: > 0 convex
  if (rho < 0 && -rho <= R) return flat;  // concave tighter than the tool: gouges anyway; keep flat step
  const double c = ((rho + h) * (rho + h) + (rho + R) * (rho + R) - R * R) / (2.0 * (rho + h) * (rho + R));
  const double theta = 2.0 * std::acos(std::clamp(c, -1.0, 1.0));
  return std::abs(rho) * theta;
}

namespace {
struct PassSampler {
  const NurbsSurface& s;
  const RasterOptions& o;
  cutter::Cutter cut;
  Vec3 axis;
  bool along_u;
  double orient;  // +1 or -1: makes the normals face the tool on average
  Vec3 cl(double t, double w) const {
    const double u = along_u ? t : w, v = along_u ? w : t;
    const Vec3 n = orient * s.normal(u, v);
    const Vec3 cc = s.point(u, v) + o.stock_allowance * n;
    return cc_to_cl(cut, cc, n, axis);
  }
};

double chord_dev(const Vec3& a, const Vec3& b, const Vec3& m) {
  const Vec3 ab = b - a;
  const double L2 = ab.squaredNorm();
  if (L2 <= 0) return (m - a).norm();
  const double t = std::clamp((m - a).dot(ab) / L2, 0.0, 1.0);
  return (a + t * ab - m).norm();
}

void refine(const PassSampler& ps, double w, double t0, const Vec3& p0, double t1, const Vec3& p1, double tol,
            int depth, std::vector<Vec3>& out) {
  const double tm = 0.5 * (t0 + t1);
  const Vec3 pm = ps.cl(tm, w);
  // check the quarter points too, so inflections between samples are not missed
  const Vec3 pq = ps.cl(0.5 * (t0 + tm), w), pr = ps.cl(0.5 * (tm + t1), w);
  const double dev = std::max({chord_dev(p0, p1, pm), chord_dev(p0, p1, pq), chord_dev(p0, p1, pr)});
  if (dev > tol && depth < 16) {
    refine(ps, w, t0, p0, tm, pm, tol, depth + 1, out);
    refine(ps, w, tm, pm, t1, p1, tol, depth + 1, out);
  } else {
    out.push_back(p1);
  }
}
}  // namespace

toolpath::Toolpath raster_toolpath(const NurbsSurface& s, const RasterOptions& o) {
  o.validate();
  const Vec3 axis = o.axis.normalized();
  // Orientation: the side of the surface the tool sees (3-axis: mean n·axis over a coarse grid ≥ 0).
  double mean_na = 0.0;
  {
    const auto [ua, ub] = s.domain_u();
    const auto [va, vb] = s.domain_v();
    for (int i = 0; i < 9; ++i)
      for (int j = 0; j < 9; ++j) mean_na += s.normal(ua + (ub - ua) * i / 8.0, va + (vb - va) * j / 8.0).dot(axis);
  }
  PassSampler ps{s, o, o.cutter, axis, o.along_u, mean_na < 0 ? -1.0 : 1.0};
  const auto [ta, tb] = o.along_u ? s.domain_u() : s.domain_v();
  const auto [wa, wb] = o.along_u ? s.domain_v() : s.domain_u();
  const double R_eff = o.cutter.kind == cutter::CutterKind::ball ? o.cutter.radius : o.cutter.corner_radius;
  const int probe = std::max(16, 4 * (o.along_u ? s.count_u() : s.count_v()));
  const int ninit = std::max(8, 2 * (o.along_u ? s.count_u() - s.degree_u() : s.count_v() - s.degree_v()) + 2);

  // parameter values of the passes
  std::vector<double> passes;
  double w = wa;
  for (int guard = 0; guard < 100000; ++guard) {
    passes.push_back(w);
    if (w >= wb) break;
    double dw = std::numeric_limits<double>::infinity();
    for (int k = 0; k < probe; ++k) {
      const double t = ta + (tb - ta) * k / (probe - 1);
      const double u = o.along_u ? t : w, v = o.along_u ? w : t;
      const MatrixXdR d = s.derivatives(u, v, 2);  // D = 3
      const Vec3 sw = (o.along_u ? d.row(1) : d.row(3)).transpose();
      const Vec3 sww = (o.along_u ? d.row(2) : d.row(6)).transpose();
      const double len = sw.norm();
      if (len < 1e-12 * s.size()) continue;  // collapsed edge: no step constraint here
      const Vec3 n = ps.orient * s.normal(u, v);
      const double kappa = -sww.dot(n) / (len * len);  // > 0 convex towards the tool
      const double step = o.step_over > 0 ? o.step_over : scallop_step(R_eff, o.scallop_height, kappa);
      dw = std::min(dw, step / len);
    }
    if (!std::isfinite(dw)) dw = (wb - wa) / 16.0;
    dw = std::max(dw, 1e-9 * (wb - wa));
    w = (w + dw >= wb - 1e-9 * (wb - wa)) ? wb : w + dw;
  }
  if (passes.size() >= 100000) throw Error("raster_toolpath: more than 100000 passes; step-over too small");

  // CL polylines of the passes
  std::vector<std::vector<Vec3>> lines;
  double top = -std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < passes.size(); ++i) {
    std::vector<Vec3> pts;
    std::vector<double> ts(ninit + 1);
    for (int k = 0; k <= ninit; ++k) ts[k] = ta + (tb - ta) * k / ninit;
    Vec3 prev = ps.cl(ts[0], passes[i]);
    pts.push_back(prev);
    for (int k = 1; k <= ninit; ++k) {
      const Vec3 next = ps.cl(ts[k], passes[i]);
      refine(ps, passes[i], ts[k - 1], prev, ts[k], next, o.chord_tolerance, 0, pts);
      prev = next;
    }
    if (o.zigzag && (i % 2 == 1)) std::reverse(pts.begin(), pts.end());
    for (const Vec3& p : pts) top = std::max(top, p.dot(axis));
    lines.push_back(std::move(pts));
  }

  toolpath::Toolpath tp;
  tp.source = "raster";
  auto add = [&](toolpath::MotionKind kind, const Vec3& a, const Vec3& b, double feed) {
    if ((b - a).norm() <= 1e-12) return;
    toolpath::Block blk;
    blk.kind = kind;
    blk.start = a;
    blk.end = b;
    blk.feed = feed;
    blk.spindle_rpm = o.spindle_rpm;
    blk.tool = o.tool;
    tp.blocks.push_back(blk);
  };
  auto lift = [&](const Vec3& p) -> Vec3 { return p + (top + o.clearance - p.dot(axis)) * axis; };
  const double plunge = o.plunge_feed > 0 ? o.plunge_feed : o.feed;
  Vec3 at = lift(lines.front().front());
  tp.blocks.reserve(16);
  for (std::size_t i = 0; i < lines.size(); ++i) {
    const auto& L = lines[i];
    if (i == 0) {
      add(toolpath::MotionKind::line, at, L.front(), plunge);
    } else if (o.zigzag) {
      add(toolpath::MotionKind::line, at, L.front(), o.feed);  // cross-feed to the next pass
    } else {
      add(toolpath::MotionKind::rapid, at, lift(at), o.feed);
      add(toolpath::MotionKind::rapid, lift(at), lift(L.front()), o.feed);
      add(toolpath::MotionKind::line, lift(L.front()), L.front(), plunge);
    }
    for (std::size_t k = 1; k < L.size(); ++k) add(toolpath::MotionKind::line, L[k - 1], L[k], o.feed);
    at = L.back();
  }
  add(toolpath::MotionKind::rapid, at, lift(at), o.feed);
  return tp;
}

}  // namespace netshape::geometry
