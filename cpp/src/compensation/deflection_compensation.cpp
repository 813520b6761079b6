#include "netshape/compensation/deflection_compensation.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <stdexcept>

#include <Eigen/QR>

#include "netshape/core/error.hpp"
#include "netshape/stock/sweep.hpp"

namespace netshape::compensation {

using deflection::DeflectionModel;
using deflection::DeflectionWorkspace;
using deflection::WallSide;

namespace {
constexpr double two_pi = 2.0 * pi;
inline double wrap(double a) { return a - two_pi * std::floor(a / two_pi); }

std::string fmt(const char* f, double a, double b = 0, double c = 0, double d = 0) {
  char buf[256];
  std::snprintf(buf, sizeof buf, f, a, b, c, d);
  return buf;
}

bool window_holds(double st, double ex, double a) { return wrap(a - st) <= ex - st + 1e-12; }

/// Engagement of one point: the window, the axial depth, whether it cuts.
struct PointCut {
  bool engaged = false;
  double phi_st = 0, phi_ex = 0, depth = 0, width = 0;
};

/// Everything a single-point evaluation needs; reused along the path.
struct PointEvaluator {
  DeflectionModel model;
  DeflectionWorkspace ws;
  double radius;
  int profile_levels;
  WallSide side;

  PointEvaluator(const DeflectionModel& m, const cutter::Cutter& c, const PathOptions& o)
      : model(m), radius(c.radius), profile_levels(o.profile_levels), side(o.side) {}

  /// Deflection at the three levels (and the profile) for the cut `pc` with the feed direction
  /// x_c (unit, XY); fills row i of `out` given the wall normal n and offset C.
  void evaluate(const PointCut& pc, const Vec2& x_c, const Vec2& n, double C, Eigen::Index i, PathWallErrors& out) {
    out.width[i] = pc.width;
    out.depth[i] = pc.depth;
    out.phi_st[i] = pc.phi_st;
    out.phi_ex[i] = pc.phi_ex;
    out.engaged[i] = pc.engaged ? 1 : 0;
    int flags = 0;
    if (pc.engaged) {
      if (window_holds(pc.phi_st, pc.phi_ex, 0.0)) flags |= 1;
      if (window_holds(pc.phi_st, pc.phi_ex, pi)) flags |= 2;
    }
    out.wall_flags[i] = flags;
    if (!pc.engaged) {
      out.error.row(i).setConstant(-C);
      out.deflection.row(i).setZero();
      out.normal_deflection[i] = out.tangential_deflection[i] = 0.0;
      out.force.row(i).setZero();
      if (profile_levels > 0) out.profile.row(i).setConstant(-C);
      return;
    }
    model.force.axial_depth = pc.depth;
    const double st = wrap(pc.phi_st);
    model.force.engagement.phi_st = st;
    model.force.engagement.phi_ex = st + std::min(pc.phi_ex - pc.phi_st, two_pi);
    ws.ensure(model);
    const Vec2 y_c(-x_c.y(), x_c.x());
    const VectorXd lv = deflection::cut_levels(pc.depth);
    const deflection::WallErrors w = deflection::wall_errors(model, ws, side, lv);
    for (int k = 0; k < 3; ++k) {
      const Vec2 d = w.deflection(k, 0) * x_c + w.deflection(k, 1) * y_c;
      out.error(i, k) = -C - d.dot(n);
      if (k == 1) {
        out.deflection.row(i) = d.transpose();
        out.normal_deflection[i] = d.dot(n);
        out.tangential_deflection[i] = d.dot(x_c);
        const Vec2 f = w.force(k, 0) * x_c + w.force(k, 1) * y_c;
        out.force.row(i) = f.transpose();
      }
    }
    if (profile_levels > 0) {
      VectorXd zs(profile_levels);
      for (int k = 0; k < profile_levels; ++k)
        zs[k] = profile_levels == 1 ? 0.0 : pc.depth * k / (profile_levels - 1);
      const deflection::WallErrors wp = deflection::wall_errors(model, ws, side, zs);
      for (int k = 0; k < profile_levels; ++k) {
        const Vec2 d = wp.deflection(k, 0) * x_c + wp.deflection(k, 1) * y_c;
        out.profile(i, k) = -C - d.dot(n);
      }
    }
  }
};

void size_result(PathWallErrors& r, Eigen::Index n, int profile_levels) {
  r.positions.resize(n, 3);
  r.error.resize(n, 3);
  r.deflection.resize(n, 2);
  r.normal_deflection.resize(n);
  r.tangential_deflection.resize(n);
  r.force.resize(n, 2);
  r.width.resize(n);
  r.depth.resize(n);
  r.phi_st.resize(n);
  r.phi_ex.resize(n);
  r.engaged.resize(n);
  r.wall_flags.resize(n);
  r.profile.resize(n, std::max(profile_levels, 0));
}

/// Unit central-difference tangent of the nominal polyline at i (one-sided at the ends), in XY.
Vec2 nominal_tangent(const Eigen::Ref<const Points3>& p, Eigen::Index i) {
  const Eigen::Index n = p.rows();
  const Eigen::Index a = i > 0 ? i - 1 : 0, b = i + 1 < n ? i + 1 : n - 1;
  Vec2 t(p(b, 0) - p(a, 0), p(b, 1) - p(a, 1));
  if (t.norm() < 1e-12) t = Vec2(p(i, 0) - p(a, 0), p(i, 1) - p(a, 1));
  return t.normalized();
}

void check_path(const Eigen::Ref<const Points3>& nominal) {
  NETSHAPE_CHECK(nominal.rows() >= 2, "path.points", nominal.rows(), "must be at least 2 points");
  for (Eigen::Index i = 0; i < nominal.rows(); ++i)
    for (int k = 0; k < 3; ++k) NETSHAPE_CHECK_FINITE("path.points", nominal(i, k));
  for (Eigen::Index i = 1; i < nominal.rows(); ++i) {
    const double d = std::hypot(nominal(i, 0) - nominal(i - 1, 0), nominal(i, 1) - nominal(i - 1, 1));
    NETSHAPE_CHECK(d > 1e-9, "path.point", static_cast<double>(i),
                   "coincides in XY with the point before it (zero-length move)");
  }
}

/// Engaged window of the cutter at `tip` moving along x_c where `in_material(point)` says what is
/// material: angular scan at the probe height, the complement of the largest gap, edges bisected.
template <typename InMaterial>
PointCut scan_window(const cutter::Cutter& cutter, const Vec3& tip, const Vec2& x_c, const stock::ImmersionOptions& o,
                     const stock::ZMap& base, InMaterial in_material) {
  const int m = o.angles;
  const Vec2 y_c(-x_c.y(), x_c.x());
  const double R = cutter.radius;
  const double zp = tip.z() + o.probe_height;
  auto point = [&](double phi) {
    const Vec2 d = std::sin(phi) * x_c + std::cos(phi) * y_c;
    return Vec3(tip.x() + R * d.x(), tip.y() + R * d.y(), zp);
  };
  std::vector<char> in(m);
  int count = 0;
  for (int k = 0; k < m; ++k) count += (in[k] = in_material(point(two_pi * k / m))) ? 1 : 0;
  PointCut pc;
  if (count == 0) return pc;
  pc.engaged = true;
  double st, ex;
  if (count == m) {
    st = 0.0;
    ex = two_pi;
  } else {
    // largest circular run of empty samples
    int best_len = 0, best_start = 0;
    for (int k = 0; k < m; ++k) {
      if (in[k]) continue;
      if (!in[(k - 1 + m) % m]) continue;  // not the start of a run
      int len = 0;
      while (len < m && !in[(k + len) % m]) ++len;
      if (len > best_len) {
        best_len = len;
        best_start = k;
      }
    }
    const int first_in = (best_start + best_len) % m;    // first engaged sample after the gap
    const int last_in = (best_start - 1 + m) % m;        // last engaged sample before the gap
    auto bisect = [&](double a_out, double b_in) {       // edge between an empty and an engaged angle
      for (int it = 0; it < 40; ++it) {
        const double mid = 0.5 * (a_out + b_in);
        if (in_material(point(mid)))
          b_in = mid;
        else
          a_out = mid;
      }
      return b_in;
    };
    const double step = two_pi / m;
    st = bisect(first_in * step - step, first_in * step);
    ex = bisect(last_in * step + step, last_in * step);
    while (ex < st) ex += two_pi;
  }
  // axial depth: material height above the tip along the engaged arc (pillar heights of the base),
  // capped at the flute length
  double depth = 0.0;
  for (int k = 0; k < m; ++k) {
    const double a = two_pi * k / m;
    if (!window_holds(st, ex, a)) continue;
    const Vec3 p = point(a);
    const double h = base.cell_height(p.x(), p.y());
    if (std::isfinite(h)) depth = std::max(depth, h - tip.z());
  }
  depth = std::min(depth, cutter.flute_length);
  if (depth <= 1e-9) return PointCut{};
  pc.phi_st = st > pi ? st - two_pi : st;
  pc.phi_ex = pc.phi_st + (ex - st);
  pc.depth = depth;
  pc.width = R * (std::cos(pc.phi_st) - std::cos(pc.phi_ex));
  return pc;
}

double seg_dist2(const Vec2& p, const Vec2& a, const Vec2& b) {
  const Vec2 ab = b - a;
  const double l2 = ab.squaredNorm();
  double t = l2 > 0 ? (p - a).dot(ab) / l2 : 0.0;
  t = std::clamp(t, 0.0, 1.0);
  return (a + t * ab - p).squaredNorm();
}

/// True if q (XY) lies within R of the polyline through the earlier points 0 … i−1 (point_of(j) gives
/// point j in XY): the material the flat end's swept discs removed before point i. Walks back from
/// i − 1 until the polyline has left the reach 2R + 2 mm of R_i.
template <typename PointOf>
bool removed_by_earlier(const Vec2& q, Eigen::Index i, const Vec2& Ri, double R, PointOf point_of) {
  if (i == 0) return false;
  const double r2 = R * R, reach = 2.0 * R + 2.0;
  Vec2 b = point_of(i - 1);
  if ((q - b).squaredNorm() < r2) return true;
  for (Eigen::Index j = i - 1; j >= 1; --j) {
    const Vec2 a = point_of(j - 1);
    if (seg_dist2(q, a, b) < r2) return true;
    if ((a - Ri).norm() > reach && (b - Ri).norm() > reach) break;
    b = a;
  }
  return false;
}

double max_abs_level(const PathWallErrors& r, int level, int* where) {
  double best = -1.0;
  int w = 0;
  for (Eigen::Index i = 0; i < r.error.rows(); ++i) {
    const double v = std::abs(r.error(i, level));
    if (!(v <= best)) {  // NaN counts as worst
      best = std::isfinite(v) ? v : std::numeric_limits<double>::infinity();
      w = static_cast<int>(i);
    }
  }
  if (where) *where = w;
  return best;
}

}  // namespace

const char* to_string(ReferenceLevel l) noexcept {
  return l == ReferenceLevel::bottom ? "bottom" : l == ReferenceLevel::middle ? "middle" : "top";
}
ReferenceLevel reference_level_from_string(const std::string& s) {
  if (s == "bottom") return ReferenceLevel::bottom;
  if (s == "middle") return ReferenceLevel::middle;
  if (s == "top") return ReferenceLevel::top;
  throw std::invalid_argument("level = " + s + ": must be \"bottom\", \"middle\" or \"top\"");
}
const char* to_string(DeflectionScheme s) noexcept {
  switch (s) {
    case DeflectionScheme::one_d: return "one-d";
    case DeflectionScheme::integrated: return "integrated";
    case DeflectionScheme::sectional: return "sectional";
    default: return "accelerated";
  }
}
DeflectionScheme deflection_scheme_from_string(const std::string& s) {
  if (s == "one-d" || s == "one_d") return DeflectionScheme::one_d;
  if (s == "integrated") return DeflectionScheme::integrated;
  if (s == "sectional") return DeflectionScheme::sectional;
  if (s == "accelerated") return DeflectionScheme::accelerated;
  throw std::invalid_argument("scheme = " + s + ": must be one-d, integrated, sectional or accelerated");
}

void PathOptions::validate() const {
  NETSHAPE_CHECK(profile_levels >= 0 && profile_levels <= 1000, "profile_levels", profile_levels,
                 "must be in 0..1000");
  immersion.validate();
}

void DeflectionCompensationOptions::validate() const {
  NETSHAPE_CHECK_FINITE("tolerance", tolerance);
  NETSHAPE_CHECK(tolerance > 0.0, "tolerance", tolerance, "must be positive [mm]");
  NETSHAPE_CHECK_FINITE("discount", discount);
  NETSHAPE_CHECK(discount > 0.0 && discount <= 1.0, "discount", discount, "must be in (0, 1]");
  NETSHAPE_CHECK(max_iterations >= 1 && max_iterations <= 100000, "max_iterations", max_iterations,
                 "must be in 1..100000");
  NETSHAPE_CHECK(anderson_depth >= 1 && anderson_depth <= 50, "anderson_depth", anderson_depth, "must be in 1..50");
  path.validate();
}

Points2 wall_normals(const Eigen::Ref<const Points3>& nominal, WallSide side) {
  check_path(nominal);
  const Eigen::Index n = nominal.rows();
  Points2 out(n, 2);
  const double s = side == WallSide::left ? 1.0 : -1.0;
  for (Eigen::Index i = 0; i < n; ++i) {
    const Eigen::Index a = i > 0 ? i - 1 : 0, b = i + 1 < n ? i + 1 : n - 1;
    Vec2 t(nominal(b, 0) - nominal(a, 0), nominal(b, 1) - nominal(a, 1));
    if (t.norm() < 1e-12) t = Vec2(nominal(i, 0) - nominal(a, 0), nominal(i, 1) - nominal(a, 1));
    t.normalize();
    out(i, 0) = -s * t.y();
    out(i, 1) = s * t.x();
  }
  return out;
}

PathWallErrors path_wall_errors(const DeflectionModel& model, const cutter::Cutter& cutter, const stock::ZMap& stock,
                                const Eigen::Ref<const Points3>& nominal, const Eigen::Ref<const Points2>& normals,
                                const Eigen::Ref<const VectorXd>& offsets, const PathOptions& options) {
  options.validate();
  cutter.validate();
  model.beam.validate();
  check_path(nominal);
  const Eigen::Index n = nominal.rows();
  NETSHAPE_CHECK(normals.rows() == n, "normals.rows", normals.rows(), "must equal the number of path points");
  NETSHAPE_CHECK(offsets.size() == n, "offsets.size", offsets.size(), "must equal the number of path points");
  for (Eigen::Index i = 0; i < n; ++i) NETSHAPE_CHECK_FINITE("offsets", offsets[i]);
  NETSHAPE_CHECK(cutter.kind == cutter::CutterKind::flat, "cutter.kind", cutter::to_string(cutter.kind),
                 "must be flat (the deflection model is the flat end mill's)");
  PathWallErrors out;
  size_result(out, n, options.profile_levels);
  for (Eigen::Index i = 0; i < n; ++i) {
    out.positions(i, 0) = nominal(i, 0) + offsets[i] * normals(i, 0);
    out.positions(i, 1) = nominal(i, 1) + offsets[i] * normals(i, 1);
    out.positions(i, 2) = nominal(i, 2);
  }
  PointEvaluator ev(model, cutter, options);
  if (options.exact_self_removal) {
    auto pos = [&](Eigen::Index j) { return Vec2(out.positions(j, 0), out.positions(j, 1)); };
    for (Eigen::Index i = 0; i < n; ++i) {
      const Vec3 tip = out.positions.row(i).transpose();
      const Vec2 xc = nominal_tangent(nominal, i);
      const Vec2 Pi = pos(i);
      const PointCut pc = scan_window(cutter, tip, xc, options.immersion, stock, [&](const Vec3& p) {
        return stock.is_material(p) && !removed_by_earlier(Vec2(p.x(), p.y()), i, Pi, cutter.radius, pos);
      });
      ev.evaluate(pc, xc, Vec2(normals(i, 0), normals(i, 1)), offsets[i], i, out);
    }
    return out;
  }
  stock::ZMap map = stock;
  for (Eigen::Index i = 0; i < n; ++i) {
    const Vec3 tip = out.positions.row(i).transpose();
    const Vec2 xc = nominal_tangent(nominal, i);
    const stock::Immersion im = stock::immersion(map, cutter, tip, Vec3(xc.x(), xc.y(), 0.0), options.immersion);
    PointCut pc;
    if (im.engaged && im.axial_depth > 1e-9) {
      pc.engaged = true;
      pc.phi_st = im.phi_st;
      pc.phi_ex = im.phi_ex;
      pc.depth = im.axial_depth;
      pc.width = im.radial_depth;
    }
    ev.evaluate(pc, xc, Vec2(normals(i, 0), normals(i, 1)), offsets[i], i, out);
    const Vec3 from = i > 0 ? Vec3(out.positions.row(i - 1).transpose()) : tip;
    stock::sweep_line(map, cutter, from, tip);
  }
  return out;
}

double one_d_compensation(const DeflectionModel& model_in, WallSide side, double width, double level_z,
                          double tolerance, int max_iterations) {
  NETSHAPE_CHECK_FINITE("width", width);
  const double R = model_in.force.radius;
  NETSHAPE_CHECK(width > 0.0 && width <= 2.0 * R, "width", width, "must be in (0, D] [mm]");
  NETSHAPE_CHECK_FINITE("level_z", level_z);
  DeflectionModel model = model_in;
  model.validate();
  DeflectionWorkspace ws(model);
  const force::MillingMode mode = side == WallSide::left ? force::MillingMode::up : force::MillingMode::down;
  const VectorXd zl = (VectorXd(1) << level_z).finished();
  auto g = [&](double C) {
    const double w = std::clamp(width + C, 1e-9, 2.0 * R);
    model.force.engagement = force::AngularEngagement::from_mode(mode, R, w);
    return deflection::wall_errors(model, ws, side, zl).error[0] - C;
  };
  double a = 0.0, ga = g(a);
  if (std::abs(ga) <= tolerance) return 0.0;
  // bracket: step in the direction of the residual, doubling
  double step = ga, b = a + step, gb = g(b);
  int k = 0;
  while (ga * gb > 0.0) {
    NETSHAPE_CHECK(++k < 60, "width", width, "1-D compensation: no root of E(W, C) = D[W + C] − C bracketed");
    a = b;
    ga = gb;
    step *= 2.0;
    b = a + step;
    if (width + b <= 0.0 || width + b > 2.0 * R)
      throw std::runtime_error("1-D compensation: no root of E(W, C) = D[W + C] - C with 0 < W + C <= D");
    gb = g(b);
  }
  // Illinois regula falsi
  int side_kept = 0;
  for (int it = 0; it < max_iterations; ++it) {
    const double c = b - gb * (b - a) / (gb - ga);
    const double gc = g(c);
    if (std::abs(gc) <= tolerance || std::abs(b - a) < 1e-12) return c;
    if (gc * gb < 0.0) {
      a = b;
      ga = gb;
      side_kept = 0;
    } else {
      if (side_kept == 1) ga *= 0.5;
      side_kept = 1;
    }
    b = c;
    gb = gc;
  }
  return b;
}

DeflectionCompensationResult compensate_deflection(const DeflectionModel& model, const cutter::Cutter& cutter,
                                                   const stock::ZMap& stock, const Eigen::Ref<const Points3>& nominal,
                                                   const DeflectionCompensationOptions& options) {
  options.validate();
  check_path(nominal);
  const Eigen::Index n = nominal.rows();
  const int level = static_cast<int>(options.level);
  const PathOptions& po = options.path;
  DeflectionCompensationResult res;
  res.scheme = options.scheme;
  res.normals = wall_normals(nominal, po.side);
  const double eps = options.tolerance, lam = options.discount;

  auto evaluate = [&](const VectorXd& C) {
    PathWallErrors r = path_wall_errors(model, cutter, stock, nominal, res.normals, C, po);
    ++res.path_evaluations;
    res.point_evaluations += n;
    res.history.push_back(max_abs_level(r, level, nullptr));
    return r;
  };
  VectorXd C = VectorXd::Zero(n);
  res.before = evaluate(C);
  if (res.before.engaged.sum() == 0)
    throw std::invalid_argument("path: never touches the stock (no point of the path engages material)");
  auto errors_of = [&](const PathWallErrors& r) { return VectorXd(r.error.col(level)); };
  auto point_name = [&](int i) {
    return fmt("point %.0f (x %.3f, y %.3f mm)", i, nominal(i, 0), nominal(i, 1));
  };
  auto finish = [&](PathWallErrors&& after) {
    res.offsets = C;
    res.after = std::move(after);
    res.positions = res.after.positions;
    const double worst = max_abs_level(res.after, level, &res.worst_index);
    return worst;
  };

  switch (options.scheme) {
    case DeflectionScheme::one_d: {
      DeflectionModel m = model;
      for (Eigen::Index i = 0; i < n; ++i) {
        if (!res.before.engaged[i] || res.before.width[i] <= 1e-9) continue;
        m.force.axial_depth = res.before.depth[i];
        const double z = deflection::cut_levels(res.before.depth[i])[level];
        C[i] = one_d_compensation(m, po.side, std::min(res.before.width[i], 2.0 * m.force.radius), z,
                                  0.01 * eps);
        res.point_evaluations += 1;
      }
      res.iterations = 1;
      const double worst = finish(evaluate(C));
      res.converged = worst <= eps;
      res.message = res.converged
                        ? fmt("one-d: max |e| %.3f um <= %.3f um", worst * 1e3, eps * 1e3)
                        : "one-d: max |e| " + fmt("%.3f um > tolerance %.3f um at ", worst * 1e3, eps * 1e3) +
                              point_name(res.worst_index) +
                              " (the 1-D root assumes a constant width; use integrated, sectional or accelerated)";
      return res;
    }
    case DeflectionScheme::integrated:
    case DeflectionScheme::accelerated: {
      const bool anderson = options.scheme == DeflectionScheme::accelerated;
      PathWallErrors cur = res.before;
      VectorXd e = errors_of(cur);
      double prev = res.history.back();
      int grew = 0;
      const int m = options.anderson_depth;
      std::vector<VectorXd> dF, dG;  // differences of f = λe and of g = C + λe
      VectorXd f_old, g_old;
      for (int it = 1; it <= options.max_iterations; ++it) {
        res.iterations = it;
        int where = 0;
        const double worst = max_abs_level(cur, level, &where);
        if (worst <= eps) {
          finish(std::move(cur));
          res.converged = true;
          res.message = std::string(to_string(options.scheme)) +
                        fmt(": converged, max |e| %.3f um <= %.3f um after %.0f evaluations", worst * 1e3, eps * 1e3,
                            static_cast<double>(res.path_evaluations));
          return res;
        }
        if (!std::isfinite(worst)) {
          finish(std::move(cur));
          res.message = std::string(to_string(options.scheme)) + ": diverged: non-finite error at " + point_name(where);
          return res;
        }
        const VectorXd f = lam * e, gk = C + f;
        VectorXd next = gk;
        if (anderson) {
          if (f_old.size() == n) {
            dF.push_back(f - f_old);
            dG.push_back(gk - g_old);
            if (static_cast<int>(dF.size()) > m) {
              dF.erase(dF.begin());
              dG.erase(dG.begin());
            }
          }
          f_old = f;
          g_old = gk;
          if (!dF.empty()) {
            const int k = static_cast<int>(dF.size());
            Eigen::MatrixXd Fm(n, k), Gm(n, k);
            for (int j = 0; j < k; ++j) {
              Fm.col(j) = dF[j];
              Gm.col(j) = dG[j];
            }
            const VectorXd gamma = Fm.colPivHouseholderQr().solve(f);
            if (gamma.allFinite()) next = gk - Gm * gamma;
          }
        }
        C = next;
        PathWallErrors trial = evaluate(C);
        const double w2 = max_abs_level(trial, level, nullptr);
        if (anderson && !(w2 <= 2.0 * worst)) {
          // the extrapolation raised the residual: restart from the plain step
          dF.clear();
          dG.clear();
          f_old.resize(0);
          C = gk;
          trial = evaluate(C);
        }
        cur = std::move(trial);
        e = errors_of(cur);
        const double now = res.history.back();
        grew = now > prev ? grew + 1 : 0;
        prev = now;
        if (grew >= 3) {
          int w = 0;
          max_abs_level(cur, level, &w);
          finish(std::move(cur));
          res.message = std::string(to_string(options.scheme)) +
                        fmt(": diverging: max |e| grew for 3 iterations in a row to %.3f um, at ", now * 1e3) +
                        point_name(w) + " (lower the discount factor or the feed)";
          return res;
        }
      }
      const double worst = finish(std::move(cur));
      res.message = std::string(to_string(options.scheme)) +
                    fmt(": iteration limit %.0f reached with max |e| %.3f um > %.3f um at ",
                        options.max_iterations, worst * 1e3, eps * 1e3) +
                    point_name(res.worst_index);
      return res;
    }
    case DeflectionScheme::sectional: {
      // Base stock (pre-path) and the removal by the tool's discs along the earlier points at the
      // trial offset of the point being solved.
      const cutter::Cutter& ct = cutter;
      const double R = ct.radius;
      PointEvaluator ev(model, cutter, po);
      PathWallErrors scratch;
      size_result(scratch, 1, po.profile_levels);
      int most = 0;
      for (Eigen::Index i = n - 1; i >= 0; --i) {
        double c = i + 1 < n ? C[i + 1] : 0.0;
        const Vec2 Ri(nominal(i, 0), nominal(i, 1)), ni(res.normals(i, 0), res.normals(i, 1));
        bool ok = false;
        int it = 0;
        double e = 0.0;
        for (it = 1; it <= options.max_iterations; ++it) {
          const Vec2 Pi = Ri + c * ni;
          const Vec2 xc = nominal_tangent(nominal, i);
          // earlier points at the trial offset
          auto trial = [&](Eigen::Index j) {
            return Vec2(Vec2(nominal(j, 0), nominal(j, 1)) + c * Vec2(res.normals(j, 0), res.normals(j, 1)));
          };
          auto removed = [&](const Vec3& p) { return removed_by_earlier(Vec2(p.x(), p.y()), i, Pi, R, trial); };
          const Vec3 tip(Pi.x(), Pi.y(), nominal(i, 2));
          const PointCut pc = scan_window(ct, tip, xc, po.immersion, stock, [&](const Vec3& p) {
            return stock.is_material(p) && !removed(p);
          });
          ev.evaluate(pc, xc, ni, c, 0, scratch);
          ++res.point_evaluations;
          e = scratch.error(0, level);
          if (!std::isfinite(e)) break;
          if (std::abs(e) <= 0.25 * eps) {
            ok = true;
            break;
          }
          c += lam * e;
        }
        most = std::max(most, it);
        C[i] = c;
        if (!ok) {
          res.iterations = most;
          finish(evaluate(C));
          res.worst_index = static_cast<int>(i);
          res.message = fmt("sectional: %.3f um left after %.0f iterations at ", std::abs(e) * 1e3,
                            static_cast<double>(options.max_iterations)) +
                        point_name(static_cast<int>(i)) + " (iteration limit or non-finite error)";
          return res;
        }
      }
      res.iterations = most;
      const double worst = finish(evaluate(C));
      res.converged = worst <= eps;
      res.message = res.converged
                        ? fmt("sectional: converged, max |e| %.3f um <= %.3f um", worst * 1e3, eps * 1e3)
                        : fmt("sectional: solved point by point, but the path evaluation leaves %.3f um > %.3f um at ",
                              worst * 1e3, eps * 1e3) +
                              point_name(res.worst_index);
      return res;
    }
  }
  return res;
}

}  // namespace netshape::compensation
