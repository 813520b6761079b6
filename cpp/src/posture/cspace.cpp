// C-space grid, boundary bisection and the MC-space move.
#include "netshape/posture/cspace.hpp"

#include <cmath>
#include <limits>
#include <string>

#include "netshape/core/error.hpp"

namespace netshape::posture {

PostureFrame PostureFrame::make(const Vec3& cc, const Vec3& normal, const Vec3& feed, const char* field) {
  NETSHAPE_CHECK(cc.allFinite(), field, cc.transpose(), "CC point must be finite [mm]");
  const double nn = normal.norm();
  NETSHAPE_CHECK(std::isfinite(nn) && nn > 1e-12, field, cc.transpose(),
                 "degenerate surface: the normal at this CC point is zero or not finite");
  PostureFrame fr;
  fr.cc = cc;
  fr.normal = normal / nn;
  Vec3 f = feed - feed.dot(fr.normal) * fr.normal;
  const double fn = f.norm();
  NETSHAPE_CHECK(std::isfinite(fn) && fn > 1e-9 * std::max(1.0, feed.norm()), field, cc.transpose(),
                 "the feed direction is zero or along the normal at this CC point");
  fr.feed = f / fn;
  fr.left = fr.normal.cross(fr.feed);
  return fr;
}

Vec3 PostureFrame::axis(double theta, double phi) const {
  return std::cos(theta) * normal + std::sin(theta) * (std::cos(phi) * feed + std::sin(phi) * left);
}

Vec2 PostureFrame::posture(const Vec3& a) const {
  const Vec3 t = a.normalized();
  const double c = std::max(-1.0, std::min(1.0, t.dot(normal)));
  const double x = t.dot(feed), y = t.dot(left);
  return {std::acos(c), (x == 0.0 && y == 0.0) ? 0.0 : std::atan2(y, x)};
}

Vec2 to_plane(const Vec2& p) { return {p[0] * std::cos(p[1]), p[0] * std::sin(p[1])}; }
Vec2 from_plane(const Vec2& q) {
  const double r = q.norm();
  return {r, r > 0 ? std::atan2(q[1], q[0]) : 0.0};
}

void CSpaceOptions::validate() const {
  NETSHAPE_CHECK(std::isfinite(theta_max) && theta_max > 0 && theta_max < 0.5 * pi, "theta_max", theta_max,
                 "must be in (0, π/2) [rad]");
  NETSHAPE_CHECK(std::isfinite(theta_step) && theta_step > 0 && theta_step <= theta_max, "theta_step", theta_step,
                 "must be in (0, theta_max] [rad]");
  NETSHAPE_CHECK(std::isfinite(phi_step) && phi_step > 0 && phi_step <= 0.5 * pi, "phi_step", phi_step,
                 "must be in (0, π/2] [rad]");
  NETSHAPE_CHECK(std::isfinite(tolerance) && tolerance > 0 && tolerance < theta_step, "tolerance", tolerance,
                 "must be in (0, theta_step) [rad]");
}

double CSpace::phi(int j) const { return -pi + j * (2.0 * pi / count_phi); }

PostureState classify(const InterferenceChecker& checker, const PostureFrame& frame, double theta, double phi) {
  const Vec3 t = frame.axis(theta, phi);
  const double r = checker.assembly().ball_radius;
  const Vec3 tip = frame.cc + r * frame.normal - r * t;
  Vec3 witness;
  if (!checker.collides(tip, t, &witness)) return PostureState::free;
  return (witness - frame.cc).dot(frame.left) > 0 ? PostureState::ca1 : PostureState::ca2;
}

namespace {
// Bisect between posture a (state sa) and b (state sb ≠ sa) along the straight segment of (θ, φ) until the
// bracket is shorter than tol in the polar plane; append the boundary point(s) of the obstacle(s) met.
void bisect_edge(const InterferenceChecker& checker, CSpace& cs, Vec2 a, PostureState sa, Vec2 b, PostureState sb) {
  const double tol = cs.options.tolerance;
  auto plane_len = [](const Vec2& p, const Vec2& q) { return (to_plane(p) - to_plane(q)).norm(); };
  while (plane_len(a, b) > tol) {
    const Vec2 m = 0.5 * (a + b);
    const PostureState sm = classify(checker, cs.frame, m[0], m[1]);
    ++cs.checks;
    if (sm == sa) {
      a = m;
    } else {
      b = m;
      sb = sm;
    }
  }
  const Vec2 mid = 0.5 * (a + b);
  if (sa != PostureState::free) cs.boundary.push_back({mid[0], mid[1], static_cast<int>(sa)});
  if (sb != PostureState::free && sb != sa) cs.boundary.push_back({mid[0], mid[1], static_cast<int>(sb)});
}
}  // namespace

CSpace compute_cspace(const InterferenceChecker& checker, const PostureFrame& frame, const CSpaceOptions& options,
                      const char* field) {
  options.validate();
  CSpace cs;
  cs.frame = frame;
  cs.options = options;
  cs.count_theta = static_cast<int>(std::floor(options.theta_max / options.theta_step + 1e-9)) + 1;
  cs.count_phi = std::max(4, static_cast<int>(std::lround(2.0 * pi / options.phi_step)));
  cs.states.resize(static_cast<std::size_t>(cs.count_theta * cs.count_phi));
  const PostureState s0 = classify(checker, frame, 0.0, 0.0);
  ++cs.checks;
  bool any_free = s0 == PostureState::free;
  for (int j = 0; j < cs.count_phi; ++j) {
    cs.states[static_cast<std::size_t>(j * cs.count_theta)] = s0;
    for (int k = 1; k < cs.count_theta; ++k) {
      const PostureState s = classify(checker, frame, cs.theta(k), cs.phi(j));
      ++cs.checks;
      cs.states[static_cast<std::size_t>(j * cs.count_theta + k)] = s;
      any_free = any_free || s == PostureState::free;
    }
  }
  if (!any_free) {
    std::ostringstream os;
    os.precision(6);
    os << "(" << frame.cc.transpose() << ") mm";
    detail::throw_invalid(field, os.str(),
                          "the tool cannot reach this CC point: every posture up to theta_max collides");
  }
  // rays: θ_k → θ_{k+1} at fixed φ_j
  for (int j = 0; j < cs.count_phi; ++j) {
    for (int k = 0; k + 1 < cs.count_theta; ++k) {
      const PostureState a = cs.state(j, k), b = cs.state(j, k + 1);
      if (a != b) bisect_edge(checker, cs, {cs.theta(k), cs.phi(j)}, a, {cs.theta(k + 1), cs.phi(j)}, b);
    }
  }
  // rings: φ_j → φ_{j+1} at fixed θ_k (k ≥ 1; the ring θ = 0 is one posture)
  const double dphi = 2.0 * pi / cs.count_phi;
  for (int k = 1; k < cs.count_theta; ++k) {
    for (int j = 0; j < cs.count_phi; ++j) {
      const int j1 = (j + 1) % cs.count_phi;
      const PostureState a = cs.state(j, k), b = cs.state(j1, k);
      if (a != b) bisect_edge(checker, cs, {cs.theta(k), cs.phi(j)}, a, {cs.theta(k), cs.phi(j) + dphi}, b);
    }
  }
  return cs;
}

Vec2 repair_posture(const InterferenceChecker& checker, const CSpace& cs, const Vec2& p, long& checks) {
  const Vec2 pp = to_plane(p);
  double best = std::numeric_limits<double>::infinity();
  Vec2 target(0.0, 0.0);
  for (int j = 0; j < cs.count_phi; ++j) {
    for (int k = 0; k < cs.count_theta; ++k) {
      if (cs.state(j, k) != PostureState::free) continue;
      const Vec2 g(cs.theta(k), cs.phi(j));
      const double d = (to_plane(g) - pp).squaredNorm();
      if (d < best) {
        best = d;
        target = g;
      }
    }
  }
  Vec2 bad = pp, good = to_plane(target);
  while ((bad - good).norm() > cs.options.tolerance) {
    const Vec2 mid = 0.5 * (bad + good);
    const Vec2 pm = from_plane(mid);
    const bool b = pm[0] > cs.options.theta_max || classify(checker, cs.frame, pm[0], pm[1]) != PostureState::free;
    ++checks;
    (b ? bad : good) = mid;
  }
  return from_plane(good);
}

Vec2 CSpace::nearest_boundary(const Vec2& p, int obstacle) const {
  const Vec2 q = to_plane(p);
  double best = std::numeric_limits<double>::infinity();
  Vec2 out(options.theta_max, obstacle == 1 ? 0.5 * pi : -0.5 * pi);
  for (const BoundaryPoint& b : boundary) {
    if (b.obstacle != obstacle) continue;
    const double d = (to_plane({b.theta, b.phi}) - q).squaredNorm();
    if (d < best) {
      best = d;
      out = {b.theta, b.phi};
    }
  }
  return out;
}

Vec2 CSpace::mc_posture(const Vec2& p) const {
  const Vec2 a = to_plane(nearest_boundary(p, 1));
  const Vec2 b = to_plane(nearest_boundary(p, 2));
  return from_plane(0.5 * (a + b));
}

}  // namespace netshape::posture
