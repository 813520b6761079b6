// Cutter assembly as solids of revolution from a profile: validation, sections, exact meridian distance.
#include "netshape/posture/assembly.hpp"

#include <cmath>
#include <limits>

#include "netshape/core/error.hpp"

namespace netshape::posture {

namespace {
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

}  // namespace netshape::posture
