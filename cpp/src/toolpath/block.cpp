#include "netshape/toolpath/block.hpp"

#include <cmath>

#include "netshape/core/error.hpp"

namespace netshape::toolpath {

PlaneAxes plane_axes(Plane p) noexcept {
  switch (p) {
    case Plane::zx: return {2, 0, 1};
    case Plane::yz: return {1, 2, 0};
    case Plane::xy:
    default: return {0, 1, 2};
  }
}

namespace {
// Angle of the point p about the centre c in the plane (a, b).
double angle_in(const Vec3& p, const Vec3& c, const PlaneAxes& ax) {
  return std::atan2(p[ax.b] - c[ax.b], p[ax.a] - c[ax.a]);
}
double radius_in(const Vec3& p, const Vec3& c, const PlaneAxes& ax) {
  return std::hypot(p[ax.a] - c[ax.a], p[ax.b] - c[ax.b]);
}
}  // namespace

double Block::sweep() const noexcept {
  if (kind != MotionKind::arc) return 0.0;
  const PlaneAxes ax = plane_axes(plane);
  const double a0 = angle_in(start, center, ax);
  const double a1 = angle_in(end, center, ax);
  double d = a1 - a0;
  const double two_pi = 2.0 * pi;
  // A full circle when start and end coincide in the plane.
  const bool closed = std::hypot(end[ax.a] - start[ax.a], end[ax.b] - start[ax.b]) <= 1e-12 * (1.0 + radius());
  if (clockwise) {
    while (d >= 0.0) d -= two_pi;
    if (closed) d = -two_pi;
    d -= two_pi * (turns - 1);
  } else {
    while (d <= 0.0) d += two_pi;
    if (closed) d = two_pi;
    d += two_pi * (turns - 1);
  }
  return d;
}

double Block::radius() const noexcept {
  if (kind != MotionKind::arc) return 0.0;
  return radius_in(start, center, plane_axes(plane));
}

double Block::length() const noexcept {
  if (kind != MotionKind::arc) return (end - start).norm();
  const PlaneAxes ax = plane_axes(plane);
  const double r0 = radius_in(start, center, ax);
  const double r1 = radius_in(end, center, ax);
  const double planar = 0.5 * (r0 + r1) * std::abs(sweep());
  const double axial = end[ax.n] - start[ax.n];
  return std::hypot(planar, axial);
}

Vec3 Block::point_at(double s) const noexcept {
  if (kind != MotionKind::arc) return start + s * (end - start);
  if (s >= 1.0) return end;
  const PlaneAxes ax = plane_axes(plane);
  const double r0 = radius_in(start, center, ax);
  const double r1 = radius_in(end, center, ax);
  const double r = r0 + s * (r1 - r0);
  const double ang = angle_in(start, center, ax) + s * sweep();
  Vec3 p;
  p[ax.a] = center[ax.a] + r * std::cos(ang);
  p[ax.b] = center[ax.b] + r * std::sin(ang);
  p[ax.n] = start[ax.n] + s * (end[ax.n] - start[ax.n]);
  return p;
}

Vec3 Block::tangent_at(double s) const noexcept {
  if (kind != MotionKind::arc) {
    const Vec3 d = end - start;
    const double n = d.norm();
    return n > 0.0 ? Vec3(d / n) : Vec3::Zero();
  }
  const PlaneAxes ax = plane_axes(plane);
  const double r0 = radius_in(start, center, ax);
  const double r1 = radius_in(end, center, ax);
  const double sw = sweep();
  const double r = r0 + s * (r1 - r0);
  const double ang = angle_in(start, center, ax) + s * sw;
  // derivative of point_at with respect to s
  Vec3 d;
  d[ax.a] = (r1 - r0) * std::cos(ang) - r * sw * std::sin(ang);
  d[ax.b] = (r1 - r0) * std::sin(ang) + r * sw * std::cos(ang);
  d[ax.n] = end[ax.n] - start[ax.n];
  const double n = d.norm();
  return n > 0.0 ? Vec3(d / n) : Vec3::Zero();
}

double Block::curvature() const noexcept {
  if (kind != MotionKind::arc) return 0.0;
  const double r = radius();
  if (r <= 0.0) return 0.0;
  // helix: kappa = r / (r^2 + c^2), c = pitch / (2 pi) = axial / sweep
  const PlaneAxes ax = plane_axes(plane);
  const double sw = sweep();
  const double c = sw != 0.0 ? (end[ax.n] - start[ax.n]) / sw : 0.0;
  return r / (r * r + c * c);
}

void Block::validate() const {
  for (int i = 0; i < 3; ++i) {
    NETSHAPE_CHECK_FINITE("block.start", start[i]);
    NETSHAPE_CHECK_FINITE("block.end", end[i]);
    NETSHAPE_CHECK_FINITE("block.center", center[i]);
  }
  NETSHAPE_CHECK_FINITE("block.feed", feed);
  NETSHAPE_CHECK(feed >= 0.0, "block.feed", feed, "must not be negative [mm/s]");
  if (kind == MotionKind::arc) {
    NETSHAPE_CHECK(radius() > 0.0, "block.radius", radius(), "arc radius must be positive [mm]");
    NETSHAPE_CHECK(turns >= 1, "block.turns", turns, "must be at least 1");
  }
}

}  // namespace netshape::toolpath
