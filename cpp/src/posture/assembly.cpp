// Cutter assembly interference by branch and bound on the axis with the AABB-tree point distance.
#include "netshape/posture/assembly.hpp"

#include <cmath>
#include <limits>

#include "netshape/core/error.hpp"

namespace netshape::posture {

void CutterAssembly::validate() const {
  NETSHAPE_CHECK(std::isfinite(ball_radius) && ball_radius > 0, "ball_radius", ball_radius, "must be positive [mm]");
  NETSHAPE_CHECK(std::isfinite(shank_radius) && shank_radius > 0, "shank_radius", shank_radius,
                 "must be positive [mm]");
  NETSHAPE_CHECK(std::isfinite(holder_radius) && holder_radius > 0, "holder_radius", holder_radius,
                 "must be positive [mm]");
  NETSHAPE_CHECK(std::isfinite(shank_length) && shank_length > ball_radius, "shank_length", shank_length,
                 "must exceed ball_radius (lengths are measured from the tip) [mm]");
  NETSHAPE_CHECK(std::isfinite(holder_length) && holder_length >= shank_length + holder_radius, "holder_length",
                 holder_length, "must be ≥ shank_length + holder_radius (lengths are measured from the tip) [mm]");
}

InterferenceChecker::InterferenceChecker(geometry::TriangleMesh obstacles, CutterAssembly assembly, double clearance,
                                         double tolerance)
    : mesh_(std::move(obstacles)), assembly_(assembly), clearance_(clearance), tolerance_(tolerance) {
  assembly_.validate();
  NETSHAPE_CHECK(std::isfinite(clearance) && clearance >= 0, "clearance", clearance, "must be ≥ 0 [mm]");
  NETSHAPE_CHECK(std::isfinite(tolerance) && tolerance > 0, "tolerance", tolerance, "must be positive [mm]");
}

namespace {
struct Interval {
  double zc, h, r;  // centre height [mm], half-length [mm], part radius [mm]
};
}  // namespace

double InterferenceChecker::search(const Vec3& tip, const Vec3& axis, double stop_below, double prune_at,
                                   Vec3* witness) const {
  const bool gap_mode = !std::isfinite(prune_at);
  const auto& a = assembly_;
  std::vector<Interval> live{{a.ball_radius, 0.0, a.ball_radius},
                             {0.5 * (a.ball_radius + a.shank_length), 0.5 * (a.shank_length - a.ball_radius),
                              a.shank_radius},
                             {0.5 * (a.shank_length + a.holder_radius + a.holder_length),
                              0.5 * (a.holder_length - a.shank_length - a.holder_radius), a.holder_radius}};
  std::vector<Interval> next;
  Points3 pts;
  VectorXd d;
  double best = std::numeric_limits<double>::infinity();
  double best_z = a.ball_radius;
  while (!live.empty()) {
    const auto n = static_cast<Eigen::Index>(live.size());
    pts.resize(n, 3);
    d.resize(n);
    for (Eigen::Index k = 0; k < n; ++k) pts.row(k) = (tip + live[static_cast<std::size_t>(k)].zc * axis).transpose();
    mesh_.distance(pts, d);
    next.clear();
    for (Eigen::Index k = 0; k < n; ++k) {
      const Interval& iv = live[static_cast<std::size_t>(k)];
      const double value = d[k] - iv.r;
      if (value < best) {
        best = value;
        best_z = iv.zc;
      }
    }
    if (best < stop_below) break;  // certainly colliding
    const double cut = gap_mode ? best - tolerance_ : prune_at;
    for (Eigen::Index k = 0; k < n; ++k) {
      const Interval& iv = live[static_cast<std::size_t>(k)];
      const double lower = d[k] - iv.r - iv.h;
      if (lower >= cut) continue;  // nothing in this interval below the cut
      if (iv.h < tolerance_) {
        if (!gap_mode) {  // undecided within the tolerance: count as colliding (free stays certified)
          best = std::min(best, lower);
          best_z = iv.zc;
          next.clear();
          break;
        }
        continue;
      }
      next.push_back({iv.zc - 0.5 * iv.h, 0.5 * iv.h, iv.r});
      next.push_back({iv.zc + 0.5 * iv.h, 0.5 * iv.h, iv.r});
    }
    if (!gap_mode && best < stop_below) break;
    live.swap(next);
  }
  if (witness) *witness = tip + best_z * axis;
  return best;
}

bool InterferenceChecker::collides(const Vec3& tip, const Vec3& axis, Vec3* witness) const {
  const double g = search(tip, axis, clearance_, clearance_, witness);
  return g < clearance_;
}

double InterferenceChecker::gap(const Vec3& tip, const Vec3& axis) const {
  return search(tip, axis, -std::numeric_limits<double>::infinity(), std::numeric_limits<double>::infinity(),
                nullptr);
}

std::vector<bool> InterferenceChecker::collides(const Eigen::Ref<const Points3>& tips,
                                                const Eigen::Ref<const Points3>& axes) const {
  NETSHAPE_CHECK(tips.rows() == axes.rows(), "axes.rows", axes.rows(), "must equal tips.rows");
  std::vector<bool> out(static_cast<std::size_t>(tips.rows()));
  for (Eigen::Index i = 0; i < tips.rows(); ++i) {
    Vec3 ax = axes.row(i).transpose();
    const double len = ax.norm();
    NETSHAPE_CHECK(std::isfinite(len) && len > 0, "axes row", i, "must be a non-zero finite vector");
    const Vec3 tip = tips.row(i).transpose();
    const Vec3 unit = ax / len;
    out[static_cast<std::size_t>(i)] = collides(tip, unit, nullptr);
  }
  return out;
}

Vec3 InterferenceChecker::closest_point(const Vec3& p) const {
  Points3 q(1, 3);
  q.row(0) = p.transpose();
  return mesh_.closest_points(q).points.row(0).transpose();
}

}  // namespace netshape::posture
