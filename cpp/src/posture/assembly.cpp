// Cutter assembly as solids of revolution from a profile; interference by branch and bound over pieces of
// the solid with the AABB-tree closest point (see assembly.hpp for the bounds).
#include "netshape/posture/assembly.hpp"

#include <cmath>
#include <limits>

#include "netshape/core/error.hpp"

namespace netshape::posture {

namespace {
constexpr double kPi = 3.14159265358979323846;
constexpr std::size_t kPieceBudget = 20000;  // pieces per query before giving up (counts as undecided)

// Distance from (x, y) to the segment (ax, ay)–(bx, by) in the meridian plane.
double segment_distance(double x, double y, double ax, double ay, double bx, double by) {
  const double ux = bx - ax, uy = by - ay, den = ux * ux + uy * uy;
  double t = den > 0 ? ((x - ax) * ux + (y - ay) * uy) / den : 0.0;
  t = std::max(0.0, std::min(1.0, t));
  return std::hypot(x - ax - t * ux, y - ay - t * uy);
}
}  // namespace

void CutterAssembly::validate() const {
  NETSHAPE_CHECK(std::isfinite(ball_radius) && ball_radius > 0, "ball_radius", ball_radius, "must be positive [mm]");
  NETSHAPE_CHECK(std::isfinite(shank_radius) && shank_radius > 0, "shank_radius", shank_radius,
                 "must be positive [mm]");
  NETSHAPE_CHECK(std::isfinite(shank_length) && shank_length > ball_radius, "shank_length", shank_length,
                 "must exceed ball_radius (lengths are measured from the tip) [mm]");
  if (holder_profile.rows() == 0) {
    NETSHAPE_CHECK(std::isfinite(holder_radius) && holder_radius > 0, "holder_radius", holder_radius,
                   "must be positive [mm]");
    NETSHAPE_CHECK(std::isfinite(holder_length) && holder_length > shank_length, "holder_length", holder_length,
                   "must exceed shank_length (lengths are measured from the tip) [mm]");
    return;
  }
  const auto& p = holder_profile;
  NETSHAPE_CHECK(p.rows() >= 2, "holder_profile.rows", p.rows(), "needs at least 2 (z, r) pairs");
  for (Eigen::Index i = 0; i < p.rows(); ++i) {
    NETSHAPE_CHECK(p.row(i).allFinite() && p(i, 1) > 0, "holder_profile", p.row(i),
                   "each (z, r) must be finite with r > 0 [mm]");
    if (i > 0) {
      NETSHAPE_CHECK(p(i, 0) >= p(i - 1, 0), "holder_profile", p.row(i), "z must not decrease [mm]");
    }
  }
  NETSHAPE_CHECK(std::abs(p(0, 0) - shank_length) <= 1e-9 * std::max(1.0, shank_length), "holder_profile",
                 p.row(0), "must start at z = shank_length (the holder starts where the shank ends) [mm]");
  NETSHAPE_CHECK(p(p.rows() - 1, 0) > p(0, 0), "holder_profile", p.row(p.rows() - 1),
                 "the last z must exceed the first [mm]");
}

std::vector<ProfileSection> CutterAssembly::sections() const {
  std::vector<ProfileSection> out{{ball_radius, shank_length, shank_radius, shank_radius}};
  if (holder_profile.rows() == 0) {
    out.push_back({shank_length, holder_length, holder_radius, holder_radius});
    return out;
  }
  for (Eigen::Index i = 0; i + 1 < holder_profile.rows(); ++i) {
    const double z0 = holder_profile(i, 0), z1 = holder_profile(i + 1, 0);
    if (z1 > z0) out.push_back({z0, z1, holder_profile(i, 1), holder_profile(i + 1, 1)});
  }
  return out;
}

double CutterAssembly::reach() const {
  double r = 2.0 * ball_radius;
  for (const ProfileSection& s : sections()) r = std::max({r, std::hypot(s.z0, s.r0), std::hypot(s.z1, s.r1)});
  return r;
}

namespace {
// Exact distance from (z, ρ) to the union of the ball (centre z = R, radius R) and the frustums [mm].
double solid_distance(const std::vector<ProfileSection>& secs, double R, double z, double rho) {
  double best = std::max(0.0, std::hypot(z - R, rho) - R);
  for (const ProfileSection& s : secs) {
    if (z >= s.z0 && z <= s.z1 && rho <= s.radius(z)) return 0.0;
    best = std::min({best, segment_distance(z, rho, s.z0, 0.0, s.z0, s.r0),
                     segment_distance(z, rho, s.z0, s.r0, s.z1, s.r1),
                     segment_distance(z, rho, s.z1, s.r1, s.z1, 0.0)});
  }
  return best;
}
}  // namespace

double CutterAssembly::distance(double z, double rho) const {
  return solid_distance(sections(), ball_radius, z, rho);
}

InterferenceChecker::InterferenceChecker(geometry::TriangleMesh obstacles, CutterAssembly assembly, double clearance,
                                         double tolerance)
    : mesh_(std::move(obstacles)), assembly_(std::move(assembly)), clearance_(clearance), tolerance_(tolerance) {
  assembly_.validate();
  NETSHAPE_CHECK(std::isfinite(clearance) && clearance >= 0, "clearance", clearance, "must be ≥ 0 [mm]");
  NETSHAPE_CHECK(std::isfinite(tolerance) && tolerance > 0, "tolerance", tolerance, "must be positive [mm]");
}

namespace {
// A piece of the solid: slab z ∈ [zc − h, zc + h] of part `part` (−1 the ball), radial range [rho0, rho1],
// angular range [psi − delta, psi + delta]; delta ≥ π: the whole disc ρ ≤ rho1 (centre on the axis).
struct Piece {
  int part;
  double zc, h, rho0, rho1, psi, delta;
  bool disc() const { return delta >= kPi; }
  double rho_mid() const { return disc() ? 0.0 : 0.5 * (rho0 + rho1); }
  // Radius of a ball about the centre that holds the piece [mm].
  double bound() const {
    if (disc()) return std::hypot(h, rho1);
    const double m = rho_mid(), c = std::cos(delta);
    auto f = [&](double r) { return r * r + m * m - 2.0 * r * m * c; };
    return std::sqrt(h * h + std::max(0.0, std::max(f(rho0), f(rho1))));
  }
};

// Split a piece in place into `out` (see assembly.hpp: z while h ≥ rho1/4, a disc into an inner disc and eight
// cells, a cell along its longest extent). Cells wholly outside the part's radius are dropped.
void split(const Piece& p, const ProfileSection& s, std::vector<Piece>& out) {
  auto z_halves = [&](Piece q) {
    q.h *= 0.5;
    for (double zc : {p.zc - q.h, p.zc + q.h}) {
      Piece c = q;
      c.zc = zc;
      c.rho1 = std::min(p.rho1, std::max(s.radius(zc - c.h), s.radius(zc + c.h)));
      if (c.rho1 > c.rho0) out.push_back(c);
    }
  };
  if (p.disc()) {
    if (p.h >= 0.25 * p.rho1) return z_halves(p);
    out.push_back({p.part, p.zc, p.h, 0.0, 0.5 * p.rho1, 0.0, kPi});
    for (int j = 0; j < 8; ++j) {
      out.push_back({p.part, p.zc, p.h, 0.5 * p.rho1, p.rho1, -kPi + (2 * j + 1) * kPi / 8, kPi / 8});
    }
    return;
  }
  const double ez = 2.0 * p.h, er = p.rho1 - p.rho0, ea = 2.0 * p.delta * p.rho1;
  if (ez >= er && ez >= ea) return z_halves(p);
  Piece a = p, b = p;
  if (er >= ea) {
    const double m = p.rho_mid();
    a.rho1 = m;
    b.rho0 = m;
  } else {
    a.delta = b.delta = 0.5 * p.delta;
    a.psi = p.psi - a.delta;
    b.psi = p.psi + b.delta;
  }
  out.push_back(a);
  out.push_back(b);
}
}  // namespace

InterferenceChecker::Outcome InterferenceChecker::search(const Vec3& tip, const Vec3& axis, double stop_below,
                                                         double prune_at, double resolution) const {
  const bool gap_mode = !std::isfinite(prune_at);
  const auto& a = assembly_;
  const std::vector<ProfileSection> secs = a.sections();
  const Vec3 e1 = axis.unitOrthogonal(), e2 = axis.cross(e1);
  std::vector<Piece> live{{-1, a.ball_radius, 0.0, 0.0, 0.0, 0.0, kPi}}, next;
  for (std::size_t k = 0; k < secs.size(); ++k) {
    const ProfileSection& s = secs[k];
    live.push_back({static_cast<int>(k), 0.5 * (s.z0 + s.z1), 0.5 * (s.z1 - s.z0), 0.0, std::max(s.r0, s.r1), 0.0,
                    kPi});
  }
  Outcome out{std::numeric_limits<double>::infinity(), +1, tip};
  Points3 pts;
  std::size_t spent = 0;
  while (!live.empty()) {
    const auto n = static_cast<Eigen::Index>(live.size());
    pts.resize(n, 3);
    for (Eigen::Index k = 0; k < n; ++k) {
      const Piece& p = live[static_cast<std::size_t>(k)];
      const double m = p.rho_mid();
      pts.row(k) = (tip + p.zc * axis + m * (std::cos(p.psi) * e1 + std::sin(p.psi) * e2)).transpose();
    }
    const geometry::ClosestPoints cp = mesh_.closest_points(pts);
    for (Eigen::Index k = 0; k < n; ++k) {
      const Vec3 q = cp.points.row(k).transpose();
      const double z = (q - tip).dot(axis);
      const double u = solid_distance(secs, a.ball_radius, z, (q - tip - z * axis).norm());
      if (u < out.upper) out = {u, out.state, q};
    }
    if (out.upper < stop_below) {
      out.state = -1;
      return out;
    }
    const double cut = gap_mode ? out.upper - tolerance_ : prune_at;
    next.clear();
    for (Eigen::Index k = 0; k < n; ++k) {
      const Piece& p = live[static_cast<std::size_t>(k)];
      const double b = p.part < 0 ? a.ball_radius : p.bound();
      if (cp.distances[k] - b >= cut) continue;  // nothing of this piece comes below the cut
      if (p.part < 0 || b < resolution) {        // exact (the ball) or as small as asked: undecided
        if (!gap_mode) out.state = 0;
        continue;
      }
      split(p, secs[static_cast<std::size_t>(p.part)], next);
    }
    spent += next.size();
    if (spent > kPieceBudget) {
      out.state = 0;
      return out;
    }
    live.swap(next);
  }
  return out;
}

bool InterferenceChecker::collides(const Vec3& tip, const Vec3& axis, Vec3* witness) const {
  const Outcome o = search(tip, axis, clearance_, clearance_, tolerance_);
  if (witness) *witness = o.witness;
  return o.state != +1;
}

int InterferenceChecker::clear_by(const Vec3& tip, const Vec3& axis, double margin) const {
  return search(tip, axis, clearance_, clearance_ + margin, std::max(tolerance_, 0.25 * margin)).state;
}

double InterferenceChecker::gap(const Vec3& tip, const Vec3& axis) const {
  return search(tip, axis, -std::numeric_limits<double>::infinity(), std::numeric_limits<double>::infinity(),
                tolerance_)
      .upper;
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
