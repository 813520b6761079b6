#include "netshape/stock/engagement.hpp"

#include <algorithm>
#include <cmath>
#include <vector>

#include "netshape/core/error.hpp"

namespace netshape::stock {

void cutting_frame(const Vec3& feed_direction, Vec3& x_c, Vec3& y_c) {
  for (int k = 0; k < 3; ++k) NETSHAPE_CHECK_FINITE("feed_direction", feed_direction[k]);
  const double h = std::hypot(feed_direction.x(), feed_direction.y());
  NETSHAPE_CHECK(h > 1e-12, "feed_direction.horizontal", h,
                 "the feed direction needs a horizontal part (the cutting frame is undefined for plunges)");
  x_c = Vec3(feed_direction.x() / h, feed_direction.y() / h, 0.0);
  y_c = Vec3(-x_c.y(), x_c.x(), 0.0);  // Z × X
}

namespace {
inline Vec3 element(const Vec3& tip, const Vec3& xc, const Vec3& yc, double r, double phi, double z) {
  return tip + Vec3(0, 0, z) + r * (std::sin(phi) * xc + std::cos(phi) * yc);
}
void check_tip(const Vec3& tip) {
  for (int k = 0; k < 3; ++k) NETSHAPE_CHECK_FINITE("tip", tip[k]);
}
}  // namespace

Vec3 element_point(const cutter::Cutter& cutter, const Vec3& tip, const Vec3& feed_direction, double phi, double z) {
  check_tip(tip);
  NETSHAPE_CHECK_FINITE("phi", phi);
  NETSHAPE_CHECK_FINITE("z", z);
  NETSHAPE_CHECK(z >= 0.0, "z", z, "height above the tip must not be negative [mm]");
  Vec3 xc, yc;
  cutting_frame(feed_direction, xc, yc);
  return element(tip, xc, yc, cutter.radius_at(z), phi, z);
}

void engaged_elements_into(const ZMap& zmap, const cutter::Cutter& cutter, const Vec3& tip,
                           const Vec3& feed_direction, const Eigen::Ref<const VectorXd>& phi,
                           const Eigen::Ref<const VectorXd>& z, MaskR& out) {
  cutter.validate();
  check_tip(tip);
  Vec3 xc, yc;
  cutting_frame(feed_direction, xc, yc);
  for (Eigen::Index b = 0; b < phi.size(); ++b) NETSHAPE_CHECK_FINITE("phi", phi[b]);
  for (Eigen::Index a = 0; a < z.size(); ++a) {
    NETSHAPE_CHECK_FINITE("z", z[a]);
    NETSHAPE_CHECK(z[a] >= 0.0, "z", z[a], "heights above the tip must not be negative [mm]");
  }
  if (out.rows() != z.size() || out.cols() != phi.size()) out.resize(z.size(), phi.size());
  for (Eigen::Index a = 0; a < z.size(); ++a) {
    const double za = z[a];
    if (za > cutter.flute_length) {
      out.row(a).setConstant(false);
      continue;
    }
    const double r = cutter.radius_at(za);
    for (Eigen::Index b = 0; b < phi.size(); ++b) out(a, b) = zmap.is_material(element(tip, xc, yc, r, phi[b], za));
  }
}

MaskR engaged_elements(const ZMap& zmap, const cutter::Cutter& cutter, const Vec3& tip, const Vec3& feed_direction,
                       const Eigen::Ref<const VectorXd>& phi, const Eigen::Ref<const VectorXd>& z) {
  MaskR out(z.size(), phi.size());
  engaged_elements_into(zmap, cutter, tip, feed_direction, phi, z, out);
  return out;
}

void ImmersionOptions::validate() const {
  NETSHAPE_CHECK(angles >= 8 && angles <= 1'000'000, "immersion.angles", angles, "must be in [8, 1e6]");
  NETSHAPE_CHECK_FINITE("immersion.probe_height", probe_height);
  NETSHAPE_CHECK(probe_height >= 0.0, "immersion.probe_height", probe_height, "must not be negative [mm]");
}

Immersion immersion(const ZMap& zmap, const cutter::Cutter& cutter, const Vec3& tip, const Vec3& feed_direction,
                    const ImmersionOptions& options) {
  cutter.validate();
  options.validate();
  check_tip(tip);
  Vec3 xc, yc;
  cutting_frame(feed_direction, xc, yc);
  const double R = cutter.radius;
  const double zp = std::min(options.probe_height, cutter.flute_length);
  auto engaged = [&](double phi) { return zmap.is_material(element(tip, xc, yc, R, phi, zp)); };
  const int n = options.angles;
  const double step = 2.0 * pi / n;
  std::vector<char> on(n);
  int count = 0;
  for (int k = 0; k < n; ++k) count += (on[k] = engaged(k * step)) ? 1 : 0;
  Immersion im;
  if (count == 0) return im;
  im.engaged = true;
  int start = 0, length = n;  // engaged arc in samples: [start, start + length)
  if (count < n) {
    // the largest circular run of free samples; the engaged arc is its complement
    int best_len = 0, best_end = 0, run = 0;
    for (int k = 0; k < 2 * n; ++k) {
      if (!on[k % n]) {
        ++run;
        if (run > best_len) { best_len = std::min(run, n); best_end = k; }
      } else {
        run = 0;
      }
    }
    start = (best_end + 1) % n;
    length = n - best_len;
  }
  auto refine = [&](double free_phi, double on_phi) {  // bisect the edge between a free and an engaged sample
    for (int it = 0; it < 60 && std::abs(on_phi - free_phi) > 1e-9; ++it) {
      const double mid = 0.5 * (free_phi + on_phi);
      if (engaged(mid)) on_phi = mid; else free_phi = mid;
    }
    return 0.5 * (free_phi + on_phi);
  };
  double phi_st = start * step, phi_ex = (start + length - 1) * step;
  if (count < n) {
    phi_st = refine(phi_st - step, phi_st);
    phi_ex = refine(phi_ex + step, phi_ex);
  } else {
    phi_st = 0.0;
    phi_ex = 2.0 * pi;
  }
  // normalise phi_st into (−π, π]
  double shift = std::floor((pi - phi_st) / (2.0 * pi)) * 2.0 * pi;
  if (phi_st + shift <= -pi) shift += 2.0 * pi;
  im.phi_st = phi_st + shift;
  im.phi_ex = phi_ex + shift;
  im.radial_depth = R * (std::cos(im.phi_st) - std::cos(im.phi_ex));
  // axial depth: material height above the tip along the engaged arc (pillar heights)
  double depth = 0.0;
  const double top = tip.z() + cutter.flute_length;
  for (int k = 0; k < length; ++k) {
    const double phi = (start + k) * step;
    const Vec3 q = element(tip, xc, yc, R, phi, 0.0);
    const double h = zmap.cell_height(q.x(), q.y());
    if (std::isnan(h)) continue;
    const double lo = std::max(tip.z(), zmap.bottom());
    depth = std::max(depth, std::min(h, top) - lo);
  }
  im.axial_depth = depth;
  return im;
}

}  // namespace netshape::stock
