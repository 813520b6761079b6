// Interference of the cutter assembly with the obstacle mesh: hierarchy traversal with certified distance
// bounds per part (see assembly.hpp).
#include <cassert>
#include <cmath>
#include <limits>

#include "netshape/core/error.hpp"
#include "netshape/posture/assembly.hpp"
#include "posture/convex_distance.hpp"
#include "posture/triangle_bvh.hpp"

namespace netshape::posture {

namespace {
constexpr int kMaxParts = 32;
constexpr double kInf = std::numeric_limits<double>::infinity();
constexpr double kTouch = 1e-9;  // [mm] a gap below this is contact
constexpr double kRound = 1e-9;  // relative rounding margin of a lower bound (as in triangle_frustum)

// One solid of the assembly at a pose: the ball (centre, radius) or a frustum, with its bounding box and,
// for a frustum, its axis segment s0–s1 and largest radius.
struct Part {
  bool ball;
  detail::Frustum f;
  Vec3 centre, lo, hi, s0, s1;
  double radius;
  double inv_len2 = 0.0;  ///< 1 / |s1 − s0|² of a frustum [1/mm²]

  // Lower bound of the distance from the box [lo, hi] to the part [mm]; a frustum's second bound is not
  // computed when the box–box distance alone reaches `cut` (the caller only asks whether the bound does).
  double box_bound(const Vec3& blo, const Vec3& bhi, double cut) const {
    if (ball) return std::sqrt(box_distance(centre, blo, bhi)) - radius;
    const double bb2 = detail::box_distance2(blo, bhi, lo, hi);
    if (cut >= 0 && bb2 >= cut * cut) return std::sqrt(bb2);
    return std::max(std::sqrt(bb2), sphere_bound(0.5 * (blo + bhi), 0.5 * (bhi - blo).norm()));
  }
  // Lower bound of the distance from the ball (m, r) to a frustum part: every point of the frustum lies within
  // its largest radius of the axis segment s0–s1 [mm].
  double sphere_bound(const Vec3& m, double r) const {
    const Vec3 u = s1 - s0;
    const double t = std::clamp((m - s0).dot(u) * inv_len2, 0.0, 1.0);
    return (m - s0 - t * u).norm() - r - radius;
  }
  // Lower bound of the distance from the plane n·x = d (n unit) to a frustum part: its signed heights over the
  // plane span the end discs' centre heights ∓ r·|n × axis|, and a triangle lies in its plane [mm].
  double plane_bound(const Vec3& n, double d) const {
    const double across = std::sqrt(std::max(0.0, 1.0 - n.dot(f.axis) * n.dot(f.axis)));
    const double h0 = n.dot(s0) - d, h1 = n.dot(s1) - d, e0 = f.r0 * across, e1 = f.r1 * across;
    return std::max(std::min(h0 - e0, h1 - e1), -std::max(h0 + e0, h1 + e1));
  }
  static double box_distance(const Vec3& p, const Vec3& blo, const Vec3& bhi) {
    return (blo - p).cwiseMax(p - bhi).cwiseMax(0.0).squaredNorm();
  }
};

int make_parts(const CutterAssembly& a, const std::vector<ProfileSection>& secs, const Vec3& tip, const Vec3& axis,
               Part* parts) {
  const double R = a.ball_radius;
  const Vec3 c = tip + R * axis;
  parts[0] = {true, {tip, axis, 0.0, 2.0 * R, R, R}, c, (c.array() - R).matrix(), (c.array() + R).matrix(), c, c, R};
  const Vec3 across = (Vec3::Ones() - axis.cwiseAbs2()).cwiseMax(0.0).cwiseSqrt();  // disc extent per unit radius
  int n = 1;
  for (const ProfileSection& s : secs) {
    const Vec3 p0 = tip + s.z0 * axis, p1 = tip + s.z1 * axis;
    Part& p = parts[n++];
    p = {false, {tip, axis, s.z0, s.z1, s.r0, s.r1}, p0, (p0 - s.r0 * across).cwiseMin(p1 - s.r1 * across),
         (p0 + s.r0 * across).cwiseMax(p1 + s.r1 * across), p0, p1, std::max(s.r0, s.r1),
         1.0 / (p1 - p0).squaredNorm()};
  }
  return n;
}
}  // namespace

InterferenceChecker::InterferenceChecker(geometry::TriangleMesh obstacles, CutterAssembly assembly, double clearance,
                                         double tolerance)
    : mesh_(std::move(obstacles)), assembly_(std::move(assembly)), clearance_(clearance), tolerance_(tolerance) {
  assembly_.validate();
  NETSHAPE_CHECK(std::isfinite(clearance) && clearance >= 0, "clearance", clearance, "must be ≥ 0 [mm]");
  NETSHAPE_CHECK(std::isfinite(tolerance) && tolerance > 0, "tolerance", tolerance, "must be positive [mm]");
  sections_ = assembly_.sections();
  NETSHAPE_CHECK(sections_.size() < kMaxParts, "holder_profile.rows", assembly_.holder_profile.rows(),
                 "at most 30 sections");
  bvh_ = std::make_shared<const detail::TriangleBvh>(mesh_);
  last_hit_ = std::make_shared<std::atomic<int>>(-1);
  gjk_runs_ = std::make_shared<std::atomic<long long>>(0);
}

InterferenceChecker::Outcome InterferenceChecker::search(const Vec3& tip, const Vec3& axis, double near, double far,
                                                         double tol, bool least) const {
  // Touching counts as overlapping: at clearance 0 a gap below kTouch collides.
  near = std::max(near, kTouch);
  far = std::max(far, kTouch);
  const detail::TriangleBvh& bvh = *bvh_;
  Part parts[kMaxParts];
  const int np = make_parts(assembly_, sections_, tip, axis, parts);
  const unsigned all = (1u << np) - 1u;
  Outcome out{kInf, +1, tip};
  double cut = far;
  struct Tally {  // GJK runs of this query, added to the checker's count on every return
    std::atomic<long long>& total;
    long long n = 0;
    ~Tally() { total.fetch_add(n, std::memory_order_relaxed); }
  } runs{*gjk_runs_};
  // Test triangle t against the parts in `mask`; true when the search is decided.
  auto test = [&](int t, unsigned mask) {
    const Vec3 &a = bvh.a[t], &b = bvh.b[t], &c = bvh.c[t];
    const Vec3 &tlo = bvh.lo[t], &thi = bvh.hi[t];
    for (int k = 0; k < np; ++k) {
      const Part& p = parts[k];
      if (!(mask >> k & 1u) || p.box_bound(tlo, thi, cut) >= cut) continue;
      detail::DistanceBounds d;
      if (p.ball) {
        d.witness = detail::closest_on_triangle(p.centre, a, b, c);
        d.lower = d.upper = std::max(0.0, (d.witness - p.centre).norm() - p.radius);
      } else {
        // cheaper than GJK: a triangle off a tilted part, a part wholly on one side of the triangle's plane, or
        // a triangle off the capsule of the part's largest radius about its axis segment. The capsule skips only
        // at cut + tol, where GJK could not have ended undecided either, so no answer changes.
        if (p.sphere_bound(bvh.m[t], bvh.r[t]) >= cut || p.plane_bound(bvh.n[t], bvh.d[t]) >= cut) continue;
        const double capsule = detail::segment_triangle_distance(p.s0, p.s1, a, b, c) - p.radius;
        if (capsule - kRound * (1.0 + p.s1.cwiseAbs().maxCoeff()) >= cut + tol) continue;
        ++runs.n;
        d = detail::triangle_frustum(a, b, c, p.f, least ? -kInf : near, cut, tol);
      }
      if (d.upper < out.upper) out.upper = d.upper, out.witness = d.witness;
      if (d.upper < near) {
        out.state = -1;
        last_hit_->store(t, std::memory_order_relaxed);
        if (!least) return true;
      } else if (d.lower < far) {
        out.state = std::min(out.state, 0);
      }
      if (least) {
        cut = std::min(far, out.upper - tol);
        if (out.upper <= 0) return true;  // nothing comes closer than touching
      }
    }
    return false;
  };
  const int hint = last_hit_->load(std::memory_order_relaxed);
  if (hint >= 0 && test(hint, all)) return out;
  struct Entry {
    int node;
    unsigned mask;
    double bound;
  };
  Entry stack[128];  // depth-first: at most 2 entries per level of a median split (< 62 levels)
  int top = 0;
  stack[top++] = {0, all, -kInf};
  while (top > 0) {
    const Entry e = stack[--top];
    if (e.bound >= cut) continue;
    const detail::BvhNode& node = bvh.nodes[static_cast<std::size_t>(e.node)];
    if (node.count > 0) {
      for (int t = node.first; t < node.first + node.count; ++t) {
        if (t != hint && test(t, e.mask)) return out;
      }
      continue;
    }
    Entry child[2];
    for (int s = 0; s < 2; ++s) {
      const detail::BvhNode& ch = bvh.nodes[static_cast<std::size_t>(s == 0 ? node.left : node.right)];
      child[s] = {s == 0 ? node.left : node.right, 0u, kInf};
      for (int k = 0; k < np; ++k) {
        if (!(e.mask >> k & 1u)) continue;
        const double lb = parts[k].box_bound(ch.lo, ch.hi, cut);
        if (lb < cut) {
          child[s].mask |= 1u << k;
          child[s].bound = std::min(child[s].bound, lb);
        }
      }
    }
    if (child[0].bound < child[1].bound) std::swap(child[0], child[1]);  // the nearer one on top
    for (const Entry& ch : child) {
      if (ch.mask) stack[top++] = ch;
    }
  }
  return out;
}

bool InterferenceChecker::collides(const Vec3& tip, const Vec3& axis, Vec3* witness) const {
  const Outcome o = search(tip, axis, clearance_, clearance_, tolerance_, witness != nullptr);
  if (witness) *witness = o.witness;
  return o.state != +1;
}

int InterferenceChecker::clear_by(const Vec3& tip, const Vec3& axis, double margin) const {
  return search(tip, axis, clearance_, clearance_ + margin, std::max(tolerance_, 0.25 * margin), false).state;
}

double InterferenceChecker::gap(const Vec3& tip, const Vec3& axis) const {
  return search(tip, axis, -kInf, kInf, tolerance_, true).upper;
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
