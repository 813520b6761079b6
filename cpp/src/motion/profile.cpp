#include "netshape/motion/profile.hpp"

#include <algorithm>
#include <cmath>

namespace netshape::motion {

double ramp_time(double v0, double v1, double a, double j) noexcept {
  const double dv = std::abs(v1 - v0);
  if (!std::isfinite(j)) return dv / a;
  return std::max(1.5 * dv / a, std::sqrt(6.0 * dv / j));
}

double ramp_distance(double v0, double v1, double a, double j) noexcept {
  // mean speed times duration (not |v1² − v0²|/2a, which cancels when v1 ≈ v0 and then disagrees
  // with the duration)
  return 0.5 * (v0 + v1) * ramp_time(v0, v1, a, j);
}

double reach_speed(double v, double length, double a, double j) noexcept {
  if (length <= 0) return v;
  const double trap = std::sqrt(v * v + 2.0 * a * length);  // Lee & Lee eq. 3 / eq. 5
  if (!std::isfinite(j)) return trap;
  // S-curve needs more distance than the trapezoid for the same change: bisect in [v, trap]
  double lo = v, hi = trap;
  for (int it = 0; it < 60 && hi - lo > 1e-12 * (1.0 + hi); ++it) {
    const double m = 0.5 * (lo + hi);
    (ramp_distance(v, m, a, j) <= length ? lo : hi) = m;
  }
  return lo;
}

namespace {
// Longest slow-down from u to an end speed in [w, u]: ramp_distance(u, ·) falls from 0 up to the
// switch between acceleration- and jerk-bound ramps, rises from there to u/3 while the jerk binds and
// falls beyond u/3, so its largest value over [w, u] is at w or at u/3.
double longest_slow_down(double u, double w, double a, double j) noexcept {
  if (u <= w) return 0.0;
  const double d = ramp_distance(u, w, a, j);
  return w < u / 3.0 ? std::max(d, ramp_distance(u, u / 3.0, a, j)) : d;
}
}  // namespace

double reach_back_speed(double w, double length, double a, double j) noexcept {
  if (length <= 0) return w;
  // every ramp needs at least the trapezoid's distance at a: u ≤ √(w² + 2aL)
  const double trap = std::sqrt(w * w + 2.0 * a * length);
  if (!std::isfinite(j)) return trap;
  double lo = w, hi = trap;  // longest_slow_down is increasing in u
  for (int it = 0; it < 60 && hi - lo > 1e-12 * (1.0 + hi); ++it) {
    const double m = 0.5 * (lo + hi);
    (longest_slow_down(m, w, a, j) <= length ? lo : hi) = m;
  }
  return lo;
}

Profile detail::make_scurve(double length, double vs, double ve, double vmax, double a, double j, double ws,
                           double we) noexcept {
  Profile p;
  p.vs = vs;
  p.ve = ve;
  p.a = a;
  p.j = j;
  const double lr = detail::fit_windows(length, vs, ve, ws, we);
  const double vlow = std::max(vs, ve);
  // jerk-limited: the largest peak whose two S-curve ramps fit in lr (bisection)
  double lo = vlow, hi = std::sqrt(vs * vs + ve * ve + 2.0 * a * lr) + 1e-9;
  for (int it = 0; it < 60 && hi - lo > 1e-12 * (1.0 + hi); ++it) {
    const double m = 0.5 * (lo + hi);
    (ramp_distance(vs, m, a, j) + ramp_distance(m, ve, a, j) <= lr ? lo : hi) = m;
  }
  const double vp = std::max(vlow, std::min(lo, std::max(vmax, vlow)));
  p.vp = vp;
  p.d[0] = ws;
  p.t[0] = ws > 0 ? ws / vs : 0.0;
  p.d[1] = ramp_distance(vs, vp, a, j);
  p.t[1] = ramp_time(vs, vp, a, j);
  p.d[3] = ramp_distance(vp, ve, a, j);
  p.t[3] = ramp_time(vp, ve, a, j);
  p.d[2] = std::max(0.0, lr - p.d[1] - p.d[3]);
  p.t[2] = vp > 0 ? p.d[2] / vp : 0.0;
  p.d[4] = we;
  p.t[4] = we > 0 ? we / ve : 0.0;
  // absorb rounding so that the distances add up to the length exactly
  const double sum = p.d[0] + p.d[1] + p.d[2] + p.d[3] + p.d[4];
  if (vp > 0) {
    p.d[2] += length - sum;
    if (p.d[2] < 0) p.d[2] = 0;
    p.t[2] = p.d[2] / vp;
  }
  p.duration = p.t[0] + p.t[1] + p.t[2] + p.t[3] + p.t[4];
  return p;
}

namespace {
// speed change from v0 to v1 over duration T, evaluated at tau
void ramp_eval(double v0, double v1, double T, bool smooth, double tau, double& s, double& v, double& acc) {
  const double dv = v1 - v0;
  if (T <= 0) {
    s = 0;
    v = v1;
    acc = 0;
    return;
  }
  if (!smooth) {
    const double a = dv / T;
    s = v0 * tau + 0.5 * a * tau * tau;
    v = v0 + a * tau;
    acc = a;
    return;
  }
  const double x = tau / T;
  s = v0 * tau + dv * T * (x * x * x - 0.5 * x * x * x * x);
  v = v0 + dv * (3 * x * x - 2 * x * x * x);
  acc = dv * (6 * x - 6 * x * x) / T;
}
}  // namespace

void Profile::eval(double tau, double& s, double& v, double& acc) const noexcept {
  const bool smooth = std::isfinite(j);
  tau = std::clamp(tau, 0.0, duration);
  double base = 0;
  if (tau <= t[0]) {
    s = vs * tau;
    v = vs;
    acc = 0;
    return;
  }
  tau -= t[0];
  base += d[0];
  if (tau <= t[1]) {
    ramp_eval(vs, vp, t[1], smooth, tau, s, v, acc);
    s += base;
    return;
  }
  tau -= t[1];
  base += d[1];
  if (tau <= t[2]) {
    s = base + vp * tau;
    v = vp;
    acc = 0;
    return;
  }
  tau -= t[2];
  base += d[2];
  if (tau <= t[3]) {
    ramp_eval(vp, ve, t[3], smooth, tau, s, v, acc);
    s += base;
    return;
  }
  tau -= t[3];
  base += d[3];
  s = std::min(base + ve * tau, d[0] + d[1] + d[2] + d[3] + d[4]);
  v = ve;
  acc = 0;
}

}  // namespace netshape::motion
