// The Z-map sweep's public API (netshape/stock/sweep.hpp): input checks, collinear-run merging,
// blocks and programs; lines and arcs are swept by line_sweep.cpp and arc_sweep.cpp.
#include "netshape/stock/sweep.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include "netshape/core/error.hpp"
#include "netshape/core/progress.hpp"
#include "stock/sweep_internal.hpp"

namespace netshape::stock {

using namespace detail;

namespace {
void check_point(const char* field, const Vec3& p) {
  for (int k = 0; k < 3; ++k) NETSHAPE_CHECK_FINITE(field, p[k]);
}
}  // namespace

void SweepOptions::validate() const {
  NETSHAPE_CHECK_FINITE("sweep.chord_tolerance", chord_tolerance);
  NETSHAPE_CHECK(chord_tolerance > 0.0, "sweep.chord_tolerance", chord_tolerance, "must be positive [mm]");
}

SweepStats& SweepStats::operator+=(const SweepStats& o) noexcept {
  moves += o.moves;
  nodes_visited += o.nodes_visited;
  nodes_lowered += o.nodes_lowered;
  removed_volume += o.removed_volume;
  rapids_cutting += o.rapids_cutting;
  return *this;
}

double lowest_reach_line(const TipProfile& p, const Vec3& a, const Vec3& b, double x, double y) noexcept {
  return detail::lowest_reach(p, detail::make_line(a, b), x, y);
}

SweepStats sweep_line(ZMap& zmap, const cutter::Cutter& cutter, const Vec3& a, const Vec3& b) {
  cutter.validate();
  check_point("line.start", a);
  check_point("line.end", b);
  return sweep_line_impl(zmap, TipProfile::of(cutter), kind_of(cutter), a, b);
}

namespace {
// Every entry of an (n, 3) array finite; the error names the entry ("starts[1, 2] = nan: …").
template <class M>
void check_finite_rows(const char* name, const M& m) {
  for (Eigen::Index k = 0; k < m.rows(); ++k)
    for (Eigen::Index c = 0; c < m.cols(); ++c)
      if (!std::isfinite(m(k, c))) {
        const std::string f = std::string(name) + "[" + std::to_string(k) + ", " + std::to_string(c) + "]";
        NETSHAPE_CHECK_FINITE(f.c_str(), m(k, c));
      }
}
}  // namespace

SweepStats sweep_lines(ZMap& zmap, const cutter::Cutter& cutter, const Eigen::Ref<const MatrixXdR>& starts,
                       const Eigen::Ref<const MatrixXdR>& ends) {
  cutter.validate();
  NETSHAPE_CHECK(starts.cols() == 3, "starts.shape[1]", starts.cols(), "must be 3 (x, y, z) [mm]");
  NETSHAPE_CHECK(ends.cols() == 3, "ends.shape[1]", ends.cols(), "must be 3 (x, y, z) [mm]");
  if (ends.rows() != starts.rows()) {
    const std::string req = "must equal starts.shape[0] = " + std::to_string(starts.rows());
    NETSHAPE_CHECK(false, "ends.shape[0]", ends.rows(), req.c_str());
  }
  check_finite_rows("starts", starts);
  check_finite_rows("ends", ends);
  const Eigen::Index n = starts.rows();
  const TipProfile p = TipProfile::of(cutter);
  const ProfileKind kind = kind_of(cutter);
  SweepStats st;
  core::Progress progress("sweep", static_cast<std::size_t>(n));
  for (Eigen::Index k = 0; k < n; ++k) {
    progress.report(static_cast<std::size_t>(k));
    const Vec3 a(starts(k, 0), starts(k, 1), starts(k, 2));
    const Vec3 b(ends(k, 0), ends(k, 1), ends(k, 2));
    st += sweep_line_impl(zmap, p, kind, a, b);
  }
  return st;
}

SweepStats sweep_polyline(ZMap& zmap, const cutter::Cutter& cutter, const Eigen::Ref<const Points3>& points,
                          bool merge_collinear) {
  cutter.validate();
  NETSHAPE_CHECK(points.rows() >= 1, "points.shape[0]", points.rows(), "needs at least one point");
  check_finite_rows("points", points);
  const TipProfile p = TipProfile::of(cutter);
  const ProfileKind kind = kind_of(cutter);
  SweepStats st;
  if (points.rows() == 1) {
    const Vec3 a = points.row(0).transpose();
    return sweep_line_impl(zmap, p, kind, a, a);
  }
  Vec3 a = points.row(0).transpose();
  Vec3 b = points.row(1).transpose();
  core::Progress progress("sweep", static_cast<std::size_t>(points.rows()));
  for (Eigen::Index k = 2; k <= points.rows(); ++k) {
    progress.report(static_cast<std::size_t>(k));
    if (k < points.rows()) {
      const Vec3 c = points.row(k).transpose();
      if (merge_collinear && toolpath::continues_run(a, b, c, 1e-9)) {  // extend the run a→b to c
        b = c;
        continue;
      }
      st += sweep_line_impl(zmap, p, kind, a, b);
      a = b;
      b = c;
    } else {
      st += sweep_line_impl(zmap, p, kind, a, b);
    }
  }
  return st;
}

SweepStats sweep_block(ZMap& zmap, const cutter::Cutter& cutter, const toolpath::Block& block,
                       const SweepOptions& options) {
  cutter.validate();
  options.validate();
  block.validate();
  const TipProfile p = TipProfile::of(cutter);
  const ProfileKind kind = kind_of(cutter);
  using toolpath::MotionKind;
  if (block.kind == MotionKind::rapid) {
    if (!options.include_rapids) return {};
    SweepStats st = sweep_line_impl(zmap, p, kind, block.start, block.end);
    st.rapids_cutting = st.nodes_lowered > 0 ? 1 : 0;
    return st;
  }
  if (block.kind == MotionKind::line) return sweep_line_impl(zmap, p, kind, block.start, block.end);

  // arcs
  const double r0 = std::hypot(block.start.x() - block.center.x(), block.start.y() - block.center.y());
  const double r1 = std::hypot(block.end.x() - block.center.x(), block.end.y() - block.center.y());
  const double sw = block.sweep();
  if (block.plane == toolpath::Plane::xy && std::abs(r1 - r0) <= 1e-9) {
    ArcSetup s;
    s.cx = block.center.x();
    s.cy = block.center.y();
    s.r = r0;
    s.th0 = std::atan2(block.start.y() - s.cy, block.start.x() - s.cx);
    s.sgn = sw < 0.0 ? -1.0 : 1.0;
    s.total = std::abs(sw);
    s.z0 = block.start.z();
    s.kz = (block.end.z() - block.start.z()) / s.total;
    SweepStats st;
    st.moves = 1;
    sweep_arc(zmap, p, kind, s, st);
    st.removed_volume *= zmap.dx() * zmap.dy();
    return st;
  }
  // other planes / varying radius: chords
  const int n = toolpath::chord_count(std::max(block.radius(), 1e-12), sw, options.chord_tolerance);
  SweepStats st;
  Vec3 a = block.start;
  for (int k = 1; k <= n; ++k) {
    const Vec3 b = k == n ? block.end : block.point_at(static_cast<double>(k) / n);
    st += sweep_line_impl(zmap, p, kind, a, b);
    a = b;
  }
  return st;
}

SweepStats sweep(ZMap& zmap, const cutter::Cutter& cutter, const toolpath::Toolpath& program,
                 const SweepOptions& options) {
  cutter.validate();
  options.validate();
  const TipProfile p = TipProfile::of(cutter);
  const ProfileKind kind = kind_of(cutter);
  SweepStats st;
  bool run = false;  // a pending run of collinear feed lines a → b
  Vec3 a = Vec3::Zero(), b = Vec3::Zero();
  auto flush = [&]() {
    if (run) st += sweep_line_impl(zmap, p, kind, a, b);
    run = false;
  };
  core::Progress progress("sweep", program.blocks.size());
  std::size_t done = 0;
  for (const toolpath::Block& blk : program.blocks) {
    progress.report(done++);
    blk.validate();
    if (blk.kind == toolpath::MotionKind::line && options.merge_collinear) {
      if (run && blk.start == b && toolpath::continues_run(a, b, blk.end, 1e-9)) {
        b = blk.end;
        continue;
      }
      flush();
      run = true;
      a = blk.start;
      b = blk.end;
      continue;
    }
    flush();
    st += sweep_block(zmap, cutter, blk, options);
  }
  flush();
  return st;
}

}  // namespace netshape::stock
