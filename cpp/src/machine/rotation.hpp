#pragma once
// Small rotations without cancellation: sin x and cos x − 1 exact to rounding, R − I for the ISO 230-1
// rotation R(a, b, c) = Rz(c)·Ry(b)·Rx(a) and for the spindle tilt Rx(a)·Ry(b). The synthesis keeps
// R − I instead of R so that micro-radian angles keep their full relative precision.
#include <cmath>

#include "netshape/core/types.hpp"

namespace netshape::machine::detail {

/// sin x and cos x − 1, exact to rounding, without cancellation for small x.
inline void sincos_m1(double x, double& s, double& cm) noexcept {
  const double ax = std::abs(x);
  if (ax < 1e-3) {
    // three terms are exact to rounding here (the first omitted terms are below 1e-21 relative)
    const double x2 = x * x;
    constexpr double k6 = 1.0 / 6.0, k20 = 1.0 / 20.0, k12 = 1.0 / 12.0, k30 = 1.0 / 30.0;
    s = x * (1.0 - x2 * k6 * (1.0 - x2 * k20));
    cm = -0.5 * x2 * (1.0 - x2 * k12 * (1.0 - x2 * k30));
  } else if (ax < 0.05) {
    const double x2 = x * x;
    // Taylor series to x^9 / x^10: the next terms are below 1e-21 relative for |x| < 0.05
    constexpr double k6 = 1.0 / 6.0, k20 = 1.0 / 20.0, k42 = 1.0 / 42.0, k72 = 1.0 / 72.0;
    constexpr double k12 = 1.0 / 12.0, k30 = 1.0 / 30.0, k56 = 1.0 / 56.0, k90 = 1.0 / 90.0;
    s = x * (1.0 - x2 * k6 * (1.0 - x2 * k20 * (1.0 - x2 * k42 * (1.0 - x2 * k72))));
    cm = -0.5 * x2 * (1.0 - x2 * k12 * (1.0 - x2 * k30 * (1.0 - x2 * k56 * (1.0 - x2 * k90))));
  } else {
    s = std::sin(x);
    const double h = std::sin(0.5 * x);
    cm = -2.0 * h * h;
  }
}

/// R(a, b, c) − I with R = Rz(c)·Ry(b)·Rx(a) [rad].
inline Mat3 rotation_minus_identity(double a, double b, double c) noexcept {
  double sa, cma, sb, cmb, sc, cmc;
  sincos_m1(a, sa, cma);
  sincos_m1(b, sb, cmb);
  sincos_m1(c, sc, cmc);
  const double ca = 1.0 + cma, cb = 1.0 + cmb, cc = 1.0 + cmc;
  Mat3 m;
  m(0, 0) = cmb + cmc + cmb * cmc;
  m(0, 1) = sa * sb * cc - ca * sc;
  m(0, 2) = ca * sb * cc + sa * sc;
  m(1, 0) = cb * sc;
  m(1, 1) = sa * sb * sc + cma + cmc + cma * cmc;
  m(1, 2) = ca * sb * sc - sa * cc;
  m(2, 0) = -sb;
  m(2, 1) = sa * cb;
  m(2, 2) = cma + cmb + cma * cmb;
  return m;
}

/// Rx(a)·Ry(b) − I [rad] (spindle tilt; squareness of Z).
inline Mat3 tilt_minus_identity(double a, double b) noexcept {
  double sa, cma, sb, cmb;
  sincos_m1(a, sa, cma);
  sincos_m1(b, sb, cmb);
  const double ca = 1.0 + cma, cb = 1.0 + cmb;
  // Rx(a) Ry(b) = [[cb, 0, sb], [sa sb, ca, -sa cb], [-ca sb, sa, ca cb]]
  Mat3 m;
  m << cmb, 0.0, sb, sa * sb, cma, -sa * cb, -ca * sb, sa, cma + cmb + cma * cmb;
  return m;
}

}  // namespace netshape::machine::detail
