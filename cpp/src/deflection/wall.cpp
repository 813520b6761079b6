#include "netshape/deflection/wall.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "netshape/core/error.hpp"

namespace netshape::deflection {

namespace {
constexpr double two_pi = 2.0 * pi;
constexpr int max_windows = 64;  // separate material windows of one instant
inline double wrap(double a) { return a - two_pi * std::floor(a / two_pi); }
}  // namespace

const char* to_string(LoadModel m) noexcept { return m == LoadModel::resultant ? "resultant" : "distributed"; }

LoadModel load_model_from_string(const std::string& s) {
  if (s == "resultant") return LoadModel::resultant;
  if (s == "distributed") return LoadModel::distributed;
  throw std::invalid_argument("load = " + s + ": must be \"resultant\" or \"distributed\"");
}

const char* to_string(WallSide s) noexcept { return s == WallSide::left ? "left" : "right"; }

WallSide wall_side_from_string(const std::string& s) {
  if (s == "left") return WallSide::left;
  if (s == "right") return WallSide::right;
  throw std::invalid_argument("side = " + s + ": must be \"left\" or \"right\"");
}

double wall_angle(WallSide side) noexcept { return side == WallSide::left ? 0.0 : pi; }

void DeflectionModel::validate() const {
  force.validate();
  beam.validate();
  NETSHAPE_CHECK(beam.length >= force.axial_depth, "stick_out", beam.length,
                 "must not be shorter than the axial depth of cut [mm]");
  NETSHAPE_CHECK_FINITE("holder_compliance", holder_compliance);
  NETSHAPE_CHECK(holder_compliance >= 0.0, "holder_compliance", holder_compliance, "must be ≥ 0 [mm/N]");
  chip.validate();
  for (const auto& w : windows) w.validate();
}

void DeflectionWorkspace::reset(const DeflectionModel& model) {
  model.validate();
  disks_ = model.force.disks();
  flutes_ = model.force.flutes;
  dz_ = model.force.axial_depth / disks_;
  radius_ = model.force.radius;
  helix_ = model.force.helix;
  depth_ = model.force.axial_depth;
  target_dz_ = model.force.disk_height;
  z_.resize(disks_);
  for (int i = 0; i < disks_; ++i) z_[i] = (i + 0.5) * dz_;
  f_.setZero(disks_, 2);
}

void DeflectionWorkspace::ensure(const DeflectionModel& model) {
  if (disks_ != model.force.disks() || flutes_ != model.force.flutes || radius_ != model.force.radius ||
      helix_ != model.force.helix || depth_ != model.force.axial_depth || target_dz_ != model.force.disk_height)
    reset(model);
}

void disk_forces(const DeflectionModel& model, DeflectionWorkspace& ws, double theta) {
  NETSHAPE_CHECK_FINITE("theta", theta);
  ws.ensure(model);
  const auto& fm = model.force;
  const double kb = fm.k_beta();
  const double dz = ws.dz_;
  const double hw = 0.5 * kb * dz;  // half angular extent of an element's helix segment [rad]
  const bool smooth = model.smooth_edges && hw > 0.0;
  // the windows as (start, span); one element's weight sums its overlaps with all of them
  double wst[max_windows], wspan[max_windows];
  int nw = 0;
  if (model.windows.empty()) {
    wst[0] = fm.engagement.phi_st;
    wspan[0] = fm.engagement.phi_ex - fm.engagement.phi_st;
    nw = 1;
  } else {
    NETSHAPE_CHECK(model.windows.size() <= static_cast<std::size_t>(max_windows), "windows.size",
                   static_cast<double>(model.windows.size()), "must be at most 64");
    for (const auto& e : model.windows) {
      wst[nw] = e.phi_st;
      wspan[nw++] = e.phi_ex - e.phi_st;
    }
  }
  const double c = fm.feed_per_tooth;
  const bool kd = fm.coefficient_model == force::FlatCoefficientModel::kline_devor;
  const auto& k = fm.linear_edge;
  const double KT = fm.kline_devor.kt, KR = fm.kline_devor.kr;
  const double gamma = two_pi / ws.flutes_;
  const auto& ext = model.chip;
  const bool extended = !ext.none();
  const double href = ext.reference_chip > 0.0 ? ext.reference_chip : c;
  // chip of flute j at immersion φ: c·sin φ plus its runout step r_j − r_{j+1}; g the cutting term
  auto step = [&](int j) {
    const int n = ws.flutes_;
    return ext.runout_rho * (std::cos(ext.runout_lambda - two_pi * j / n) -
                             std::cos(ext.runout_lambda - two_pi * ((j + 1) % n) / n));
  };
  auto g = [&](double h) { return ext.chip_exponent == 1.0 ? h : href * std::pow(h / href, ext.chip_exponent); };
  for (int i = 0; i < ws.disks_; ++i) {
    double sx = 0.0, sy = 0.0;
    for (int j = 0; j < ws.flutes_; ++j) {
      const double phi = theta + j * gamma - kb * ws.z_[i];
      double w = 0.0;
      for (int q = 0; q < nw; ++q) {
        const double u = wrap(phi - wst[q]), span = wspan[q];
        if (smooth) {
          // overlap of [u − hw, u + hw] with the window [0, span], the window repeated every 2π
          double ov = 0.0;
          for (int s = -1; s <= 1; ++s) {
            const double a = u - hw + s * two_pi, b = u + hw + s * two_pi;
            ov += std::max(0.0, std::min(b, span) - std::max(a, 0.0));
          }
          w += ov / (2.0 * hw);
        } else if (u <= span) {
          w += 1.0;
        }
      }
      w = std::min(1.0, w);
      if (w <= 0.0) continue;
      const double sp = std::sin(phi), cp = std::cos(phi);
      const double ww = w * dz;
      double h = std::max(c * sp, 0.0);
      if (extended) {
        const double hj = c * sp + step(j);
        if (hj <= 0.0) continue;  // the flute before left the surface here: no contact
        h = g(hj);
      }
      if (!kd) {
        const double ft = (k.ktc * h + k.kte) * ww, fr = (k.krc * h + k.kre) * ww;
        sx += -ft * cp - fr * sp;
        sy += ft * sp - fr * cp;
      } else {
        // paper eq. 1–5 in its angle α = π − φ
        const double sa = sp, ca = -cp;
        const double tc = h;  // c·sin α = c·sin φ (clamped; with the chip extension as above)
        const double dFT = KT * tc * ww, dFR = KR * dFT;
        sx += -dFR * sa + dFT * ca;
        sy += dFR * ca + dFT * sa;
      }
    }
    ws.f_(i, 0) = sx;
    ws.f_(i, 1) = sy;
  }
}

Vec2 deflection_from_forces(const DeflectionModel& model, const DeflectionWorkspace& ws, double z) {
  const double L = model.beam.length;
  const double x = L - z;
  const double fx = ws.forces().col(0).sum(), fy = ws.forces().col(1).sum();
  if (model.load == LoadModel::resultant) {
    const double l = L - 0.5 * model.force.axial_depth;
    const double g = model.beam.influence(x, l) + model.holder_compliance;
    return Vec2(fx * g, fy * g);
  }
  double dx = model.holder_compliance * fx, dy = model.holder_compliance * fy;
  for (int i = 0; i < ws.disks(); ++i) {
    const double g = model.beam.influence(x, L - ws.heights()[i]);
    dx += ws.forces()(i, 0) * g;
    dy += ws.forces()(i, 1) * g;
  }
  return Vec2(dx, dy);
}

double generation_angle(const DeflectionModel& model, WallSide side, double z) {
  return wall_angle(side) + model.force.k_beta() * z;
}

WallErrors wall_errors(const DeflectionModel& model, DeflectionWorkspace& ws, WallSide side,
                       const Eigen::Ref<const VectorXd>& z) {
  ws.ensure(model);
  WallErrors out;
  const Eigen::Index k = z.size();
  out.z = z;
  out.error.resize(k);
  out.deflection.resize(k, 2);
  out.force.resize(k, 2);
  const double ny = side == WallSide::left ? 1.0 : -1.0;  // wall normal = ny·Y_c
  for (Eigen::Index a = 0; a < k; ++a) {
    NETSHAPE_CHECK_FINITE("z", z[a]);
    NETSHAPE_CHECK(z[a] >= 0.0 && z[a] <= model.beam.length, "z", z[a], "must lie between the tip and the clamp [mm]");
    disk_forces(model, ws, generation_angle(model, side, z[a]));
    const Vec2 d = deflection_from_forces(model, ws, z[a]);
    out.deflection.row(a) = d.transpose();
    out.force(a, 0) = ws.forces().col(0).sum();
    out.force(a, 1) = ws.forces().col(1).sum();
    out.error[a] = -d.y() * ny;
  }
  return out;
}

VectorXd cut_levels(double axial_depth) { return (VectorXd(3) << 0.0, 0.5 * axial_depth, axial_depth).finished(); }

double max_force(const DeflectionModel& model, DeflectionWorkspace& ws, int samples) {
  NETSHAPE_CHECK(samples >= 1 && samples <= 1000000, "samples", samples, "must be in 1..1000000");
  ws.ensure(model);
  double best = 0.0;
  const double period = two_pi / model.force.flutes;
  for (int s = 0; s < samples; ++s) {
    disk_forces(model, ws, period * s / samples);
    best = std::max(best, std::hypot(ws.forces().col(0).sum(), ws.forces().col(1).sum()));
  }
  return best;
}

}  // namespace netshape::deflection
