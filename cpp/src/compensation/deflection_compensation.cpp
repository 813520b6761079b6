// Tool-deflection compensation of a 2-D contour (netshape/compensation/deflection_compensation.hpp):
// option names and checks, the 1-D scheme, and the integrated, sectional and accelerated schemes.
#include "netshape/compensation/deflection_compensation.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <stdexcept>

#include <Eigen/QR>

#include "netshape/core/error.hpp"
#include "netshape/stock/sweep.hpp"
#include "compensation/deflection_path_internal.hpp"

namespace netshape::compensation {

using deflection::DeflectionModel;
using deflection::DeflectionWorkspace;
using deflection::WallSide;
using namespace detail;

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

  const Eigen::Index n_active = options.active.size();
  NETSHAPE_CHECK(n_active == 0 || n_active == n, "active.size", n_active, "must be 0 or the number of path points");
  // A corner point (the path turns there by more than corner_turn) starts the wall of the move out of
  // it; the offset its own engagement asks for (the turn's, one instant) cannot be written without
  // over- or undercutting the wall that follows it, so it takes the offset of the point after it and
  // its own error is no target (it is not an active point of the iteration).
  Eigen::VectorXi act = options.active.size() ? options.active : Eigen::VectorXi::Ones(n);
  std::vector<Eigen::Index> corners;
  for (Eigen::Index i = 0; i < n; ++i)
    if (act[i] && is_corner(nominal, i)) {
      corners.push_back(i);
      act[i] = 0;
    }
  auto is_active = [&](Eigen::Index i) { return act[i] != 0; };
  auto tie = [&](VectorXd& c) {
    for (auto it = corners.rbegin(); it != corners.rend(); ++it) c[*it] = c[*it + 1];
  };

  // every evaluation is remembered when it is the best so far (smallest max |e| over the active points)
  double best_worst = std::numeric_limits<double>::infinity();
  VectorXd best_C;
  PathWallErrors best_eval;
  auto evaluate = [&](const VectorXd& C) {
    PathWallErrors r = path_wall_errors(model, cutter, stock, nominal, res.normals, C, po);
    ++res.path_evaluations;
    res.point_evaluations += n;
    const double worst = max_abs_level(r, level, nullptr, act);
    res.history.push_back(worst);
    if (worst < best_worst) {
      best_worst = worst;
      best_C = C;
      best_eval = r;
    }
    return r;
  };
  VectorXd C = VectorXd::Zero(n);
  res.before = evaluate(C);
  if (res.before.engaged.sum() == 0)
    throw std::invalid_argument("path: never touches the stock (no point of the path engages material)");
  auto errors_of = [&](const PathWallErrors& r) {
    VectorXd e = r.error.col(level);
    for (Eigen::Index i = 0; i < n; ++i)
      if (!is_active(i)) e[i] = 0.0;
    return e;
  };
  auto point_name = [&](int i) {
    return fmt("point %.0f (x %.3f, y %.3f mm)", i, nominal(i, 0), nominal(i, 1));
  };
  // Never worse than the program as written: an active point whose |e| ends above its uncompensated
  // |e| (by more than 1 % of the tolerance) has its offset halved, six times at most, then zeroed.
  auto never_worse = [&](PathWallErrors&& after) {
    const double slack = 0.01 * eps;
    for (int round = 0; round <= 7; ++round) {
      bool worse = false;
      for (Eigen::Index i = 0; i < n; ++i) {
        if (!is_active(i)) continue;
        const double a = std::abs(after.error(i, level)), b = std::abs(res.before.error(i, level));
        if (!(a <= b + slack)) {
          worse = true;
          C[i] = round < 6 ? 0.5 * C[i] : 0.0;
        }
      }
      if (!worse || round == 7) break;
      tie(C);
      after = evaluate(C);
    }
    return std::move(after);
  };
  auto finish = [&](PathWallErrors&& after) {
    res.after = never_worse(std::move(after));
    res.offsets = C;
    res.positions = res.after.positions;
    return max_abs_level(res.after, level, &res.worst_index, act);
  };
  // a scheme that stops short of the tolerance leaves its best iterate, not its last
  auto finish_best = [&]() {
    C = best_C;
    return finish(PathWallErrors(best_eval));
  };

  switch (options.scheme) {
    case DeflectionScheme::one_d: {
      DeflectionModel m = model;
      for (Eigen::Index i = 0; i < n; ++i) {
        if (!is_active(i) || !res.before.engaged[i] || res.before.width[i] <= 1e-9) continue;
        m.force.axial_depth = res.before.depth[i];
        const double z = deflection::cut_levels(res.before.depth[i])[level];
        C[i] = one_d_compensation(m, po.side, std::min(res.before.width[i], 2.0 * m.force.radius), z,
                                  0.01 * eps);
        res.point_evaluations += 1;
      }
      res.iterations = 1;
      tie(C);
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
        const double worst = max_abs_level(cur, level, &where, act);
        if (worst <= eps) {
          const double left = finish(std::move(cur));
          res.converged = left <= eps;
          res.message = std::string(to_string(options.scheme)) +
                        fmt(res.converged ? ": converged, max |e| %.3f um <= %.3f um after %.0f evaluations"
                                          : ": converged, but the never-worse guard left %.3f um > %.3f um after "
                                            "%.0f evaluations",
                            left * 1e3, eps * 1e3, static_cast<double>(res.path_evaluations));
          return res;
        }
        if (!std::isfinite(worst)) {
          finish_best();
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
        tie(C);
        PathWallErrors trial = evaluate(C);
        const double w2 = max_abs_level(trial, level, nullptr, act);
        if (anderson && !(w2 <= 2.0 * worst)) {
          // the extrapolation raised the residual: restart from the plain step
          dF.clear();
          dG.clear();
          f_old.resize(0);
          C = gk;
          tie(C);
          trial = evaluate(C);
        }
        cur = std::move(trial);
        e = errors_of(cur);
        const double now = res.history.back();
        grew = now > prev ? grew + 1 : 0;
        prev = now;
        if (grew >= 3) {
          int w = 0;
          max_abs_level(cur, level, &w, act);
          finish_best();
          res.message = std::string(to_string(options.scheme)) +
                        fmt(": diverging: max |e| grew for 3 iterations in a row to %.3f um, at ", now * 1e3) +
                        point_name(w) + " (lower the discount factor or the feed)";
          return res;
        }
      }
      const double worst = finish_best();
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
      auto nominal_xy = [&](Eigen::Index j) { return Vec2(nominal(j, 0), nominal(j, 1)); };
      SweptIndex swept;
      int most = 0;
      for (Eigen::Index i = n - 1; i >= 0; --i) {
        if (!is_active(i)) continue;  // a wall a later pass cuts away stays as programmed (C = 0)
        double c = i + 1 < n ? C[i + 1] : 0.0;
        const Vec2 Ri(nominal(i, 0), nominal(i, 1)), ni(res.normals(i, 0), res.normals(i, 1));
        bool ok = false;
        int it = 0;
        double e = 0.0;
        for (it = 1; it <= options.max_iterations; ++it) {
          const Vec2 Pi = Ri + c * ni;
          const Vec2 xc = nominal_tangent(nominal, i);
          // earlier points at the trial offset: each lies |c| from its nominal point, so the grid of the
          // nominal moves answers for it while its reach covers R + |c|
          auto trial = [&](Eigen::Index j) {
            return Vec2(Vec2(nominal(j, 0), nominal(j, 1)) + c * Vec2(res.normals(j, 0), res.normals(j, 1)));
          };
          if (!(R + std::abs(c) <= swept.reach()))
            swept.build(n, nominal_xy, R + std::max(2.0 * std::abs(c), 0.5));
          auto removed = [&](const Vec3& p) {
            const Vec2 q(p.x(), p.y());
            return swept.near_before(q, i - 1, R, trial) || (i > 0 && in_last_sweep(q, trial(i - 1), Pi, R));
          };
          const Vec3 tip(Pi.x(), Pi.y(), nominal(i, 2));
          const PointCut pc = scan_window(ct, tip, xc, po.immersion, stock, [&](const Vec3& p) {
            return material_at(stock, p) && !removed(p);
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
      tie(C);
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
