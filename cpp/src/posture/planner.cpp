// Posture planning: raw → MC-space → MB-spline smoothing → repair.
#include "netshape/posture/planner.hpp"

#include <cmath>
#include <limits>
#include <string>

#include "netshape/core/error.hpp"
#include "netshape/core/progress.hpp"
#include "netshape/posture/mb_spline.hpp"

namespace netshape::posture {

void PlanOptions::validate() const {
  cspace.validate();
  NETSHAPE_CHECK(passes >= 0 && passes <= 1000, "passes", passes, "must be in [0, 1000]");
  NETSHAPE_CHECK(std::isfinite(vector_length) && vector_length >= 0, "vector_length", vector_length,
                 "must be ≥ 0 [mm] (0 = holder_length)");
}

int PostureSet::collision_count() const {
  int c = 0;
  for (bool b : collides) c += b ? 1 : 0;
  return c;
}

int PlanResult::repaired_count() const {
  int c = 0;
  for (bool b : repaired) c += b ? 1 : 0;
  return c;
}

namespace {
std::string point_name(Eigen::Index i) { return "CC point " + std::to_string(i); }

void fill(PostureSet& set, Eigen::Index i, const PostureFrame& fr, double radius, const Vec2& angles, bool hit) {
  const Vec3 t = fr.axis(angles[0], angles[1]);
  set.axes.row(i) = t.transpose();
  set.tips.row(i) = (fr.cc + radius * fr.normal - radius * t).transpose();
  set.angles.row(i) = angles.transpose();
  set.collides[static_cast<std::size_t>(i)] = hit;
}

void size(PostureSet& set, Eigen::Index n) {
  set.tips.resize(n, 3);
  set.axes.resize(n, 3);
  set.angles.resize(n, 2);
  set.collides.assign(static_cast<std::size_t>(n), false);
}
}  // namespace

PlanResult plan(const InterferenceChecker& checker, const Eigen::Ref<const Points3>& cc,
                const Eigen::Ref<const Points3>& normals, const PlanOptions& options) {
  options.validate();
  const Eigen::Index n = cc.rows();
  NETSHAPE_CHECK(n >= 2, "cc.rows", n, "a path needs at least 2 CC points");
  NETSHAPE_CHECK(normals.rows() == n, "normals.rows", normals.rows(), "must equal the number of CC points");
  for (Eigen::Index i = 0; i < n; ++i) {
    NETSHAPE_CHECK(cc.row(i).allFinite(), point_name(i).c_str(), cc.row(i), "CC point must be finite [mm]");
  }
  const double radius = checker.assembly().ball_radius;
  const double length = options.vector_length > 0 ? options.vector_length : checker.assembly().holder_length;
  PlanResult res;
  res.cc = cc;
  res.s.resize(n);
  res.s[0] = 0.0;
  for (Eigen::Index i = 1; i < n; ++i) {
    const double ds = (cc.row(i) - cc.row(i - 1)).norm();
    NETSHAPE_CHECK(ds > 1e-9, point_name(i).c_str(), cc.row(i), "coincides with the CC point before it");
    res.s[i] = res.s[i - 1] + ds;
  }
  res.normals.resize(n, 3);
  res.feeds.resize(n, 3);
  std::vector<PostureFrame> frames;
  frames.reserve(static_cast<std::size_t>(n));
  for (Eigen::Index i = 0; i < n; ++i) {
    const Eigen::Index a = std::max<Eigen::Index>(0, i - 1), b = std::min<Eigen::Index>(n - 1, i + 1);
    const Vec3 feed = (cc.row(b) - cc.row(a)).transpose();
    const std::string name = point_name(i);
    frames.push_back(PostureFrame::make(cc.row(i).transpose(), normals.row(i).transpose(), feed, name.c_str()));
    res.normals.row(i) = frames.back().normal.transpose();
    res.feeds.row(i) = frames.back().feed.transpose();
  }
  res.cspaces.reserve(static_cast<std::size_t>(n));
  core::Progress progress("C-space", static_cast<std::size_t>(n));
  for (Eigen::Index i = 0; i < n; ++i) {
    progress.report(static_cast<std::size_t>(i));
    const std::string name = point_name(i);
    res.cspaces.push_back(compute_cspace(checker, frames[static_cast<std::size_t>(i)], options.cspace, name.c_str()));
    res.checks += res.cspaces.back().checks;
  }
  size(res.raw, n);
  size(res.mc, n);
  size(res.smoothed, n);
  size(res.final_, n);
  res.repaired.assign(static_cast<std::size_t>(n), false);
  Points3 start(n, 3), end(n, 3);
  for (Eigen::Index i = 0; i < n; ++i) {
    const auto& fr = frames[static_cast<std::size_t>(i)];
    const auto& cs = res.cspaces[static_cast<std::size_t>(i)];
    fill(res.raw, i, fr, radius, Vec2(0.0, 0.0), cs.state(0, 0) != PostureState::free);
    const Vec2 m = cs.mc_posture(Vec2(0.0, 0.0));
    const bool hit = classify(checker, fr, m[0], m[1]) != PostureState::free;
    ++res.checks;
    fill(res.mc, i, fr, radius, m, hit);
    start.row(i) = (fr.cc + radius * fr.normal).transpose();
    end.row(i) = start.row(i) + length * res.mc.axes.row(i);
  }
  const Points3 smooth_end = mb_smooth(end, options.passes);
  const double theta_max = options.cspace.theta_max;
  for (Eigen::Index i = 0; i < n; ++i) {
    const auto& fr = frames[static_cast<std::size_t>(i)];
    const auto& cs = res.cspaces[static_cast<std::size_t>(i)];
    Vec3 t = (smooth_end.row(i) - start.row(i)).transpose();
    const Vec2 p = fr.posture(t / t.norm());
    const bool hit = classify(checker, fr, p[0], p[1]) != PostureState::free;
    ++res.checks;
    fill(res.smoothed, i, fr, radius, p, hit);
    Vec2 q = p;
    if (hit || p[0] > theta_max) {
      q = repair_posture(checker, cs, p, res.checks);
      res.repaired[static_cast<std::size_t>(i)] = true;
    }
    const bool final_hit = classify(checker, fr, q[0], q[1]) != PostureState::free;
    ++res.checks;
    fill(res.final_, i, fr, radius, q, final_hit);
  }
  return res;
}

double max_posture_change(const Eigen::Ref<const VectorXd>& s, const Eigen::Ref<const Points3>& axes) {
  NETSHAPE_CHECK(s.size() == axes.rows(), "s.size", s.size(), "must equal axes.rows");
  double best = 0.0;
  for (Eigen::Index i = 0; i + 1 < axes.rows(); ++i) {
    const Vec3 a = axes.row(i).transpose().normalized(), b = axes.row(i + 1).transpose().normalized();
    const double ang = std::atan2(a.cross(b).norm(), a.dot(b));
    const double ds = s[i + 1] - s[i];
    NETSHAPE_CHECK(ds > 0, "s", s[i + 1], "path length must increase");
    best = std::max(best, ang / ds);
  }
  return best;
}

}  // namespace netshape::posture
