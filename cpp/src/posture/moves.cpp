// Between-point motion: certified sweep check of joint-linear moves and rotary subdivision to a chord tolerance.
#include "netshape/posture/moves.hpp"

#include <cmath>

#include "netshape/core/error.hpp"
#include "netshape/posture/cspace.hpp"

namespace netshape::posture {

namespace {
// Tip and axis in the workpiece frame of joints j (5).
void pose(const Kinematics& kin, const VectorXd& j, Vec3& tip, Vec3& axis) {
  MatrixXdR row = j.transpose();
  Points3 t, a;
  forward_kinematics(kin, row, t, a);
  tip = t.row(0).transpose();
  axis = a.row(0).transpose();
}

void check_joints(const Eigen::Ref<const VectorXd>& j, const char* field) {
  NETSHAPE_CHECK(j.size() == 5 && j.allFinite(), field, j.transpose(), "must be 5 finite joints (X Y Z tilt C)");
}

// Unit vector at fraction u along the great circle from unit a to unit b (a straight lerp if they coincide).
Vec3 slerp(const Vec3& a, const Vec3& b, double u) {
  const double ang = std::atan2(a.cross(b).norm(), a.dot(b));
  if (ang < 1e-12) return ((1 - u) * a + u * b).normalized();
  return ((std::sin((1 - u) * ang) * a + std::sin(u * ang) * b) / std::sin(ang)).normalized();
}
}  // namespace

double move_speed_bound(const Kinematics& kin, const CutterAssembly& assembly, const Eigen::Ref<const VectorXd>& j0,
                        const Eigen::Ref<const VectorXd>& j1) {
  check_joints(j0, "j0");
  check_joints(j1, "j1");
  const double dx = (j1.head<3>() - j0.head<3>()).norm();
  const double rot = std::abs(j1[3] - j0[3]) + std::abs(j1[4] - j0[4]);
  const double lever = kin.kind == MachineKind::table_ac
                           ? std::max((j0.head<3>() - kin.table_centre).norm(), (j1.head<3>() - kin.table_centre).norm())
                           : kin.pivot_length;
  return dx + rot * (lever + assembly.reach());
}

MoveCheck check_move(const InterferenceChecker& checker, const Kinematics& kin, const Eigen::Ref<const VectorXd>& j0,
                     const Eigen::Ref<const VectorXd>& j1, double min_step) {
  NETSHAPE_CHECK(std::isfinite(min_step) && min_step > 0 && min_step < 1, "min_step", min_step, "must be in (0, 1)");
  const double speed = move_speed_bound(kin, checker.assembly(), j0, j1);
  const VectorXd dj = j1 - j0;
  MoveCheck out;
  std::vector<std::pair<double, double>> stack{{0.0, 1.0}};  // sub-steps, the leftmost on top
  Vec3 tip, axis;
  while (!stack.empty()) {
    const auto [l0, l1] = stack.back();
    stack.pop_back();
    const double lm = 0.5 * (l0 + l1);
    pose(kin, j0 + lm * dj, tip, axis);
    const int state = checker.clear_by(tip, axis, 0.5 * speed * (l1 - l0));
    ++out.checks;
    if (state > 0) continue;
    if (state < 0 || l1 - l0 < min_step) {
      out.collides = true;
      out.at = lm;
      return out;
    }
    stack.push_back({lm, l1});
    stack.push_back({l0, lm});
  }
  return out;
}

std::vector<MoveCheck> check_moves(const InterferenceChecker& checker, const Kinematics& kin,
                                   const Eigen::Ref<const MatrixXdR>& joints, double min_step) {
  NETSHAPE_CHECK(joints.cols() == 5, "joints.cols", joints.cols(), "must be 5 (X Y Z tilt C)");
  std::vector<MoveCheck> out;
  for (Eigen::Index i = 0; i + 1 < joints.rows(); ++i) {
    out.push_back(check_move(checker, kin, joints.row(i).transpose(), joints.row(i + 1).transpose(), min_step));
  }
  return out;
}

namespace {
struct ClPoint {
  Vec3 tip, axis, cc, normal;
  double source;
};

// Depth-first repair of the moves of one path; appends to the plan the points after `a`.
struct MoveRepair {
  const InterferenceChecker& checker;
  const Kinematics& kin;
  const PlanOptions& options;
  MovePlan& plan;
  std::vector<ClPoint> points;

  VectorXd joints(const ClPoint& p, const VectorXd& near) const {
    Points3 t(2, 3), a(2, 3);
    Vec3 tip, axis;
    pose(kin, near, tip, axis);
    t << tip.transpose(), p.tip.transpose();
    a << axis.transpose(), p.axis.transpose();
    return inverse_kinematics(kin, t, a, near[4]).row(1).transpose();
  }

  ClPoint middle(const ClPoint& a, const ClPoint& b) const {
    const double R = checker.assembly().ball_radius;
    ClPoint m{Vec3::Zero(), slerp(a.axis, b.axis, 0.5), 0.5 * (a.cc + b.cc), (a.normal + b.normal).normalized(),
              0.5 * (a.source + b.source)};
    const PostureFrame fr = PostureFrame::make(m.cc, m.normal, b.cc - a.cc, "inserted CL point");
    Vec2 p = fr.posture(m.axis);
    if (p[0] > options.cspace.theta_max || classify(checker, fr, p[0], p[1]) != PostureState::free) {
      const CSpace cs = compute_cspace(checker, fr, options.cspace, "inserted CL point");
      plan.checks += cs.checks;
      p = repair_posture(checker, cs, p, plan.checks);
    }
    ++plan.checks;
    m.axis = fr.axis(p[0], p[1]);
    m.tip = m.cc + R * m.normal - R * m.axis;
    return m;
  }

  void refine(const ClPoint& a, const VectorXd& ja, const ClPoint& b, const VectorXd& jb, int depth, bool top) {
    const MoveCheck c = check_move(checker, kin, ja, jb);
    plan.checks += c.checks;
    if (top && c.collides) ++plan.colliding_before;
    if (!c.collides || depth == 0) {
      points.push_back(b);
      return;
    }
    const ClPoint m = middle(a, b);
    const VectorXd jm = joints(m, ja);
    ++plan.inserted;
    refine(a, ja, m, jm, depth - 1, false);
    refine(m, jm, b, jb, depth - 1, false);
  }
};
}  // namespace

MovePlan repair_moves(const InterferenceChecker& checker, const Kinematics& kin, const PlanResult& result,
                      const PlanOptions& options, int max_depth) {
  options.validate();
  NETSHAPE_CHECK(max_depth >= 0 && max_depth <= 16, "max_depth", max_depth, "must be in [0, 16]");
  const Eigen::Index n = result.final_.tips.rows();
  NETSHAPE_CHECK(n >= 1 && result.cc.rows() == n, "plan.final.rows", n, "must equal the CC points (≥ 1)");
  MovePlan plan;
  MoveRepair rep{checker, kin, options, plan, {}};
  auto point = [&](Eigen::Index i) {
    return ClPoint{result.final_.tips.row(i).transpose(), result.final_.axes.row(i).transpose(),
                   result.cc.row(i).transpose(), result.normals.row(i).transpose(), static_cast<double>(i)};
  };
  const MatrixXdR joints = inverse_kinematics(kin, result.final_.tips, result.final_.axes);
  rep.points.push_back(point(0));
  for (Eigen::Index i = 0; i + 1 < n; ++i) {
    rep.refine(point(i), joints.row(i).transpose(), point(i + 1), joints.row(i + 1).transpose(), max_depth, true);
  }
  const auto m = static_cast<Eigen::Index>(rep.points.size());
  plan.tips.resize(m, 3);
  plan.axes.resize(m, 3);
  plan.source.resize(m);
  for (Eigen::Index k = 0; k < m; ++k) {
    const ClPoint& p = rep.points[static_cast<std::size_t>(k)];
    plan.tips.row(k) = p.tip.transpose();
    plan.axes.row(k) = p.axis.transpose();
    plan.source[k] = p.source;
  }
  return plan;
}

MovePlan plan_program(const InterferenceChecker& checker, const Kinematics& kin, const PlanResult& result,
                      const PlanOptions& options, double approach, double chord, int max_depth) {
  NETSHAPE_CHECK(std::isfinite(approach) && approach >= 0, "approach", approach, "must be ≥ 0 [mm]");
  MovePlan plan = repair_moves(checker, kin, result, options, max_depth);
  Points3 tips, axes;
  VectorXd src;
  subdivide_rotary(kin, plan.tips, plan.axes, chord, tips, axes, &src);
  for (Eigen::Index k = 0; k < src.size(); ++k) {  // map back to CC indices through the repair's sources
    const auto i = static_cast<Eigen::Index>(std::floor(src[k]));
    const double u = src[k] - static_cast<double>(i);
    src[k] = u > 0 ? (1 - u) * plan.source[i] + u * plan.source[i + 1] : plan.source[i];
  }
  const Eigen::Index m = tips.rows(), e = approach > 0 ? 1 : 0;
  plan.tips.resize(m + 2 * e, 3);
  plan.axes.resize(m + 2 * e, 3);
  plan.source.resize(m + 2 * e);
  plan.tips.middleRows(e, m) = tips;
  plan.axes.middleRows(e, m) = axes;
  plan.source.segment(e, m) = src;
  if (e) {
    plan.tips.row(0) = tips.row(0) + approach * axes.row(0);
    plan.axes.row(0) = axes.row(0);
    plan.source[0] = -1.0;
    plan.tips.row(m + 1) = tips.row(m - 1) + approach * axes.row(m - 1);
    plan.axes.row(m + 1) = axes.row(m - 1);
    plan.source[m + 1] = static_cast<double>(result.cc.rows());
  }
  plan.joints = inverse_kinematics(kin, plan.tips, plan.axes);
  plan.move_collides.clear();
  for (const MoveCheck& c : check_moves(checker, kin, plan.joints)) {
    plan.move_collides.push_back(c.collides);
    plan.checks += c.checks;
  }
  return plan;
}

void subdivide_rotary(const Kinematics& kin, const Eigen::Ref<const Points3>& tips,
                      const Eigen::Ref<const Points3>& axes, double chord, Points3& out_tips, Points3& out_axes,
                      VectorXd* source) {
  NETSHAPE_CHECK(std::isfinite(chord) && chord > 0, "chord", chord, "must be positive [mm]");
  NETSHAPE_CHECK(tips.rows() == axes.rows() && tips.rows() >= 1, "axes.rows", axes.rows(), "must equal tips.rows");
  std::vector<Vec3> t_out, a_out;
  std::vector<double> s_out;
  const MatrixXdR joints = inverse_kinematics(kin, tips, axes);
  constexpr int kSamples = 16, kMaxDepth = 12;
  // Deviation of the joint-linear move j0 → j1 from the chord p0 → p1 [mm].
  auto deviation = [&](const VectorXd& j0, const VectorXd& j1, const Vec3& p0, const Vec3& p1) {
    double dev = 0.0;
    const Vec3 d = p1 - p0;
    const double dd = d.squaredNorm();
    Vec3 tip, axis;
    for (int k = 1; k < kSamples; ++k) {
      pose(kin, j0 + (static_cast<double>(k) / kSamples) * (j1 - j0), tip, axis);
      const double u = dd > 0 ? std::max(0.0, std::min(1.0, (tip - p0).dot(d) / dd)) : 0.0;
      dev = std::max(dev, (tip - p0 - u * d).norm());
    }
    return dev;
  };
  for (Eigen::Index i = 0; i < tips.rows(); ++i) {
    t_out.push_back(tips.row(i).transpose());
    a_out.push_back(axes.row(i).transpose());
    s_out.push_back(static_cast<double>(i));
    if (i + 1 == tips.rows()) break;
    const Vec3 p0 = tips.row(i).transpose(), p1 = tips.row(i + 1).transpose();
    const Vec3 a0 = axes.row(i).transpose().normalized(), a1 = axes.row(i + 1).transpose().normalized();
    // pieces [u0, u1] of the chord, refined left to right until each keeps the tolerance
    std::vector<std::pair<double, int>> stack{{1.0, 0}};
    double u0 = 0.0;
    VectorXd j0 = joints.row(i).transpose();
    while (!stack.empty()) {
      const auto [u1, depth] = stack.back();
      Points3 tp(1, 3), ap(1, 3);
      tp.row(0) = ((1 - u1) * p0 + u1 * p1).transpose();
      ap.row(0) = slerp(a0, a1, u1).transpose();
      const VectorXd j1 = u1 == 1.0 ? VectorXd(joints.row(i + 1).transpose())
                                    : VectorXd(inverse_kinematics(kin, tp, ap, j0[4]).row(0).transpose());
      if (depth < kMaxDepth && deviation(j0, j1, (1 - u0) * p0 + u0 * p1, tp.row(0).transpose()) > chord) {
        stack.push_back({0.5 * (u0 + u1), depth + 1});
        continue;
      }
      stack.pop_back();
      if (u1 < 1.0) {
        t_out.push_back(tp.row(0).transpose());
        a_out.push_back(ap.row(0).transpose());
        s_out.push_back(static_cast<double>(i) + u1);
      }
      u0 = u1;
      j0 = j1;
    }
  }
  const auto n = static_cast<Eigen::Index>(t_out.size());
  out_tips.resize(n, 3);
  out_axes.resize(n, 3);
  for (Eigen::Index k = 0; k < n; ++k) {
    out_tips.row(k) = t_out[static_cast<std::size_t>(k)].transpose();
    out_axes.row(k) = a_out[static_cast<std::size_t>(k)].transpose();
  }
  if (source) source->resize(n);
  if (source) *source = Eigen::Map<const VectorXd>(s_out.data(), n);
}

}  // namespace netshape::posture
