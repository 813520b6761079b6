// Arc geometry for the planner: per-axis bounds of the tangent and curvature vector over an arc
// window, the pieces an arc is cut into, curvature vectors at segment ends.
#include "motion/planner/geometry.hpp"

#include <cmath>
#include <utility>

#include "motion/planner/blend_bounds.hpp"
#include "motion/planner/state.hpp"

namespace netshape::motion::detail {

namespace {
// smallest and largest cos and sin over the angles between p0 and p1 [rad]
void trig_range(double p0, double p1, double& cmin, double& cmax, double& smin, double& smax) {
  if (p0 > p1) std::swap(p0, p1);
  cmin = std::min(std::cos(p0), std::cos(p1));
  cmax = std::max(std::cos(p0), std::cos(p1));
  smin = std::min(std::sin(p0), std::sin(p1));
  smax = std::max(std::sin(p0), std::sin(p1));
  const double tau = 2.0 * pi;
  auto inside = [&](double at) { return std::floor((p1 - at) / tau) >= std::ceil((p0 - at) / tau); };  // at + k·2π
  if (inside(0.0)) cmax = 1.0;
  if (inside(pi)) cmin = -1.0;
  if (inside(0.5 * pi)) smax = 1.0;
  if (inside(1.5 * pi)) smin = -1.0;
}
}  // namespace

int arc_piece_count(const Segment& s) {
  const double sweep = std::abs(s.block.sweep()) * s.length() / s.full_length;
  return std::clamp(static_cast<int>(std::ceil(sweep / arc_piece_angle - 1e-9)), 1, max_arc_pieces);
}

void arc_bounds(const Segment& s, double s0, double s1, Vec3& U, Vec3& K, Vec3 (&Ua)[2], Vec3 (&Ka)[2]) {
  const toolpath::Block& b = s.block;
  const auto ax = toolpath::plane_axes(b.plane);
  const double r0 = std::hypot(b.start[ax.a] - b.center[ax.a], b.start[ax.b] - b.center[ax.b]);
  const double r1 = std::hypot(b.end[ax.a] - b.center[ax.a], b.end[ax.b] - b.center[ax.b]);
  const double sw = b.sweep(), dn = b.end[ax.n] - b.start[ax.n];
  const double ang0 = std::atan2(b.start[ax.b] - b.center[ax.b], b.start[ax.a] - b.center[ax.a]);
  double cmin, cmax, smin, smax;
  trig_range(ang0 + sw * s0 / s.full_length, ang0 + sw * s1 / s.full_length, cmin, cmax, smin, smax);
  const double mc = std::max(std::abs(cmin), std::abs(cmax)), ms = std::max(std::abs(smin), std::abs(smax));
  const double rmin = std::min(r0, r1), rmax = std::max(r0, r1), dr = rmax - rmin;
  const double rho = std::hypot(rmin * sw, dn);  // |dp/df| (lower bound when the radius varies)
  U[ax.a] = std::min(1.0, (rmax * std::abs(sw) * ms + dr) / rho);
  U[ax.b] = std::min(1.0, (rmax * std::abs(sw) * mc + dr) / rho);
  U[ax.n] = std::min(1.0, std::abs(dn) / rho);
  const double c = sw != 0.0 ? dn / sw : 0.0;
  const double kappa = std::max(r0 / (r0 * r0 + c * c), r1 / (r1 * r1 + c * c)) * (1.0 + 1e-9);
  K[ax.a] = kappa * mc;
  K[ax.b] = kappa * ms;
  K[ax.n] = 0.0;
  if (dr > 1e-9 * rmax || sw == 0.0) {  // a spiral: the ramp terms are the unsigned bounds
    for (int d = 0; d < 2; ++d) {
      Ua[d] = U;
      Ka[d] = K;
    }
    return;
  }
  // constant radius r0 = r1: u = (r·sw·(−sin φ, cos φ) + dn·e_n) / ρ and κn = −κ·(cos φ, sin φ),
  // φ = ang0 + sw·s / full_length
  const double rho0 = std::hypot(r0 * sw, dn), R = r0 * sw / rho0;
  const double kappa0 = r0 / (r0 * r0 + c * c) * (1.0 + 1e-9);
  const double e = 1e-12;  // rounding of the ranges
  double rg[3][4];  // per axis: largest and smallest u_i, largest and smallest κn_i
  rg[ax.a][0] = std::max(-R * smin, -R * smax) + e;
  rg[ax.a][1] = std::min(-R * smin, -R * smax) - e;
  rg[ax.b][0] = std::max(R * cmin, R * cmax) + e;
  rg[ax.b][1] = std::min(R * cmin, R * cmax) - e;
  rg[ax.n][0] = dn / rho0 + e;
  rg[ax.n][1] = rg[ax.n][0] - 2 * e;
  rg[ax.a][2] = -kappa0 * cmin;
  rg[ax.a][3] = -kappa0 * cmax;
  rg[ax.b][2] = -kappa0 * smin;
  rg[ax.b][3] = -kappa0 * smax;
  rg[ax.n][2] = rg[ax.n][3] = 0.0;
  for (int i = 0; i < 3; ++i) {
    double u[2], k[2];
    ramp_terms(rg[i][0], rg[i][1], rg[i][2], rg[i][3], U[i], K[i], u, k);
    for (int d = 0; d < 2; ++d) {
      Ua[d][i] = u[d];
      Ka[d][i] = k[d];
    }
  }
}

Vec3 curvature_vector(const Segment& s, bool at_end) {
  if (s.kind == SegmentKind::line) return Vec3::Zero();
  if (s.kind == SegmentKind::blend) {
    // the trimmed end (bezier_u gives exactly 0 and 1 at the untrimmed ends)
    const double u = s.bezier_u(at_end ? s.full_length - s.trim_end : s.trim_start);
    const Vec3 d1 = bezier_d1(s.ctrl, u), d2 = bezier_d2(s.ctrl, u);
    const double n2 = d1.squaredNorm();
    return n2 > 0 ? Vec3((d2 - d1 * (d1.dot(d2) / n2)) / n2) : Vec3::Zero();
  }
  const Vec3 p = s.point_at(at_end ? s.length() : 0.0);
  const auto ax = toolpath::plane_axes(s.block.plane);
  Vec3 r = Vec3::Zero();
  r[ax.a] = s.block.center[ax.a] - p[ax.a];
  r[ax.b] = s.block.center[ax.b] - p[ax.b];
  const double rn = r.norm();
  return rn > 0 ? Vec3(r * (s.block.curvature() / rn)) : Vec3::Zero();
}

}  // namespace netshape::motion::detail
