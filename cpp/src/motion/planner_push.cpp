// How a program block enters the planner: push() validates it, builds its node, and sets the junction
// with the previous block by the corner rule (the blend rule's blends: planner_blend.cpp); the limits
// and pass record of a node; the last block's node cut into arc pieces once its end is known.
#include <algorithm>
#include <cmath>
#include <limits>

#include "netshape/motion/corner.hpp"
#include "planner_geometry.hpp"
#include "planner_state.hpp"

namespace netshape::motion::detail {

namespace {
constexpr double tangent_angle = 1e-6;  // [rad] below this a junction counts as tangent
// the blend rule blends turns with tangent_angle < θ < π − 1e-3, told apart by sin(θ/2)
const double sin_half_tangent = std::sin(0.5 * tangent_angle), sin_half_reversal = std::cos(0.5e-3);

// quadratic corner bound next to curves: v·d/ts + κ·v² ≤ A
double jump_speed(double acc, double d, double ts, double kappa) {
  const double b = d / ts;
  if (kappa <= 0) return b > 0 ? acc / b : inf;
  return 2.0 * acc / (b + std::sqrt(b * b + 4.0 * kappa * acc));
}
}  // namespace

Status PlannerState::push(const toolpath::Block& b, const CubicControls* cubic) noexcept {
  if (finished_) return fail("push() after finish()");
  // a full buffer first: a streaming caller pushes until buffer_full, so every block meets this
  // test once more than the others (a bad block is reported when there is room for it)
  if (capacity_ - (tail_ - head_) < nodes_per_push || blocks_in_buffer() > options_.lookahead)
    return Status::buffer_full;
  if (!b.start.allFinite() || !b.end.allFinite() || !b.center.allFinite() || !std::isfinite(b.feed) || b.feed < 0)
    return fail("block has a non-finite coordinate or a negative feed");
  if (cubic) {
    if (const char* why = cubic_error(b, *cubic)) return fail(why);
  }
  const bool arc = b.kind == toolpath::MotionKind::arc;
  if (arc && !(b.radius() > 0)) return fail("arc radius must be positive");
  if (arc && b.turns < 1) return fail("arc turns must be at least 1");
  // a cubic block is built in scratch_ here (its length is the curve's); source: pushed_ below
  if (cubic) init_cubic_node(scratch_, b, *cubic, pushed_);
  const double len = cubic ? scratch_.segment.full_length : b.length();
  if (!(len > 1e-9)) return Status::ok;  // nothing to move
  if (have_last_ && (b.start - last_point_).norm() > 1e-6 * (1.0 + last_point_.norm()))
    return fail("block does not start where the previous one ended");
  const long source = pushed_++;
  last_point_ = b.end;
  have_last_ = true;
  const bool rapid = b.kind == toolpath::MotionKind::rapid;
  const bool jerk_mode = jerk_limited_;

  const bool has_prev = tail_ > head_ && tail_ - 1 >= frozen_;
  const long first = tail_ - 1;  // the previous block's node (it is cut into pieces below)
  const double ts2 = options_.ts2;
  const bool jump_rule = options_.rule == CornerRule::vector || options_.rule == CornerRule::per_axis;
  const double wf = window_periods();  // constant-speed window on each side of a velocity jump [ts2]

  // a line's unit direction (Block::tangent_at's arithmetic), found once: set_limits, the corner
  // here and the next block's corner read it
  const Vec3 dir = arc || cubic ? Vec3::Zero() : Vec3((b.end - b.start) / len);
  const Vec3 prev_dir = last_dir_;
  last_dir_ = dir;
  const bool prev_cubic = last_cubic_;
  last_cubic_ = cubic != nullptr;
  // the junction with the previous block (its node is final up to its end trim)
  Vec3 u1 = Vec3::Zero(), u2 = Vec3::Zero();
  double sin_half = 0.0;
  bool blend_here = false;
  const bool prev_line = has_prev && node(first).segment.kind == SegmentKind::line;
  if (has_prev) {
    u1 = prev_line ? prev_dir : end_tangent(node(first).segment);
    u2 = arc ? b.tangent_at(0.0) : cubic ? bezier_start_direction(scratch_.segment.ctrl) : dir;
    // sin(θ/2) = |u2 − u1|/2 for unit tangents: the blend rule needs no angle
    sin_half = 0.5 * (u2 - u1).norm();
    blend_here = options_.rule == CornerRule::blend && sin_half > sin_half_tangent && sin_half < sin_half_reversal;
  }
  // The new node: the whole block, bounds over all of it, until its end is known. A line is built in
  // the ring slot where it will stay when what goes in before it is known now: nothing, or the one
  // node of a blend between two lines (append_line_blend). Else (arcs, an arc before, blends in jerk
  // mode) it is built in scratch_ and copied in by append().
  const bool in_place = !arc && !cubic && (!has_prev || (prev_line && (!blend_here || !jerk_mode)));
  Node& nn = in_place ? nodes_[ring_slot(tail_ + (blend_here ? 1 : 0))] : scratch_;
  if (cubic) {
    // built above (nn is scratch_)
  } else if (arc) {
    nn = Node{};
    nn.segment = Segment::arc(b, source);
    arc_bounds(nn.segment, 0.0, nn.segment.full_length, nn.tangent_bound, nn.curvature_bound, nn.ramp_tangent,
               nn.ramp_curvature);
  } else {
    // Segment::line field by field (a line's ctrl and table are never read: copy_segment hands
    // them out as zeros); then every field of the Node the planner reads before the freeze
    if (!in_place) nn = Node{};
    nn.segment.kind = SegmentKind::line;
    nn.segment.block = b;
    nn.segment.full_length = len;
    nn.segment.trim_start = nn.segment.trim_end = 0.0;
    nn.segment.curvature = nn.segment.curvature_rate = 0.0;
    nn.segment.source = source;
    nn.tangent_bound.setZero();
    nn.curvature_bound.setZero();
    nn.start = nn.end = NodeEnd{};
    nn.geometry = Geometry::in_node;
  }
  nn.block = source;
  nn.feed_cap = (rapid || b.feed <= 0) ? inf : b.feed;
  nn.v_max = nn.feed_cap;
  set_limits(nn, arc || cubic ? nullptr : &dir, cubic ? &cubic_table(source).minima : nullptr);
  const double first_piece = arc     ? nn.segment.full_length / arc_piece_count(nn.segment)
                             : cubic ? nn.segment.full_length / cubic_piece_count()
                                     : nn.segment.full_length;
  if (jump_rule) nn.end.window = wf * ts2 * std::min(nn.v_max, first_piece / (4.0 * wf * ts2));
  nn.extent = options_.rule == CornerRule::blend ? Extent::whole_block_blend_pending : Extent::whole_block;

  if (!has_prev) {
    nn.v_junction = nn.v_corner = 0.0;  // start from rest
    append(nn);
    back_pass(tail_ - 1);
    return Status::ok;
  }
  if (blend_here) {
    // next to a cubic block (a smoothed run, already fit_share·ε from the program) the blend keeps to
    // `tolerance`; between programmed pieces to `corner_tolerance` when it is set
    blend_tolerance_ = cubic || prev_cubic || !(options_.corner_tolerance > 0) ? options_.tolerance
                                                                               : options_.corner_tolerance;
    append_corner_blend(first, nn, u1, u2, sin_half, source);
    append(nn);
    back_pass(first);
    return Status::ok;
  }

  const double theta = turn_angle(u1, u2);
  const double amin = moving_axes_min(limits_.acceleration, u1, u2);
  split_last_block();
  Node& p = node(tail_ - 1);  // the previous block's last piece
  const double vcap = std::min(p.v_max, nn.feed_cap);
  double v = vcap;
  bool jump = false;
  const Vec3 dk = jerk_mode ? Vec3(curvature_vector(nn.segment, false) - curvature_vector(p.segment, true))
                            : Vec3::Zero();
  if (theta > tangent_angle) {
    // next to arcs the vertex straddling second differences also see the centripetal part
    // (a cubic block's curvature at the joint)
    const double kappa = std::max(p.segment.kind == SegmentKind::arc     ? p.segment.block.curvature()
                                  : p.segment.kind == SegmentKind::blend ? curvature_vector(p.segment, true).norm()
                                                                         : 0.0,
                                  arc     ? nn.segment.block.curvature()
                                  : cubic ? curvature_vector(nn.segment, false).norm()
                                          : 0.0);
    switch (options_.rule) {
      case CornerRule::paper:
        v = std::max(paper_corner_speed(amin, options_.ts1, theta), options_.allowable_speed_difference);
        break;
      case CornerRule::vector:
        v = jump_speed(amin, (u2 - u1).norm(), ts2, kappa);
        if (jerk_mode) {
          // third differences: a velocity step Δv gives |Δv|/ts2², an acceleration step |Δa|/ts2
          const double jmin = moving_axes_min(limits_.jerk, u1, u2);
          v = std::min(v, jump_speed(jmin * ts2, (u2 - u1).norm(), ts2, dk.norm()));
        }
        jump = true;
        break;
      case CornerRule::per_axis:
        v = inf;
        for (int i = 0; i < 3; ++i)
          v = std::min(v, jump_speed(limits_.acceleration[i], std::abs(u2[i] - u1[i]), ts2, kappa));
        if (jerk_mode)
          for (int i = 0; i < 3; ++i)
            v = std::min(v, jump_speed(limits_.jerk[i] * ts2, std::abs(u2[i] - u1[i]), ts2, std::abs(dk[i])));
        jump = true;
        break;
      case CornerRule::junction_deviation: {
        // theta is the turn between the tangents; Klipper's δ maps scv with the moving-axes minimum
        const double dev = options_.square_corner_velocity > 0
                               ? klipper_junction_deviation(options_.square_corner_velocity, amin)
                               : options_.junction_deviation;
        const double aj = options_.junction_accel == JunctionAccel::along_change
                              ? junction_acceleration(limits_.acceleration, u1, u2, options_.junction_accel)
                              : amin;
        v = junction_deviation_speed(aj, dev, theta);
        break;
      }
      case CornerRule::blend: v = 0.0; break;  // reversal: stop
    }
    v = std::min(v, vcap);
  } else if (jerk_mode && options_.rule != CornerRule::paper && options_.rule != CornerRule::junction_deviation &&
             !((cubic || p.segment.kind == SegmentKind::blend) &&
               curvature_continuous(curvature_vector(p.segment, true), curvature_vector(nn.segment, false)))) {
    // tangent junction where the curvature jumps (line ↔ arc, arcs of other radii): the acceleration
    // steps by v²·Δ(κn); its third difference |Δa_i|/ts2 gets half of J_i, the S-curve ramps on both
    // sides the other half. (Next to a cubic block the branch is skipped where the curvature vectors
    // agree up to rounding, curvature_continuous(): the joints of one C² spline.)
    v = std::min(v, curvature_step_speed(dk));
    if (dk.norm() > 1e-12) {
      mark_curvature_step(p, false);
      mark_curvature_step(nn, true);
      update_pass(tail_ - 1);
    }
  }
  if (jump_rule) {
    if (jump) {
      v = std::min({v, p.segment.length() / (4.0 * wf * ts2), first_piece / (4.0 * wf * ts2)});
      p.end.window = wf * ts2 * v;
      nn.start.window = wf * ts2 * v;
    } else {
      p.end.window = 0.0;
    }
    p.end.velocity_jump = jump;
    nn.start.velocity_jump = jump;
    update_pass(tail_ - 1);
  }
  nn.v_corner = v;
  nn.v_junction = std::min(v, nn.v_max);
  append(nn);
  back_pass(first);
  return Status::ok;
}

void PlannerState::finish() noexcept {
  if (finished_) return;
  finished_ = true;
  if (tail_ > frozen_) {
    const long first = tail_ - 1;
    Node& t = node(first);
    if (t.extent == Extent::whole_block_blend_pending) t.extent = Extent::whole_block;
    t.segment.trim_end = 0.0;
    t.end.window = 0.0;
    t.end.velocity_jump = false;
    split_last_block();
    update_pass(first);
    back_pass(first);
  }
}

AxisMinima PlannerState::axis_minima(const Segment& s) const noexcept {
  const Vec3 moving = s.moving_axes();
  AxisMinima m;
  m.acceleration = min_over_moving(limits_.acceleration, moving);
  m.velocity = min_over_moving(limits_.velocity, moving);
  m.jerk = min_over_moving(limits_.jerk, moving);
  return m;
}

void PlannerState::set_limits(Node& n, const Vec3* line_dir, const AxisMinima* minima) const noexcept {
  const Segment& s = n.segment;
  if (s.kind == SegmentKind::line && !jerk_limited_ && options_.rule != CornerRule::paper) {
    // the common case below without the moving-axes minima it does not use
    const Vec3 u = line_dir ? *line_dir : s.block.tangent_at(0.0);
    n.bound = SpeedBound::path;
    n.v_max = std::min(n.v_max, along(limits_.velocity, u));
    n.path_accel = along(limits_.acceleration, u);
    n.path_jerk = inf;
    return;
  }
  const AxisMinima mm = minima ? *minima : axis_minima(s);
  const double amin = mm.acceleration, vmin = mm.velocity, jmin = mm.jerk;
  const bool jerk = std::isfinite(jmin);
  n.bound = SpeedBound::path;
  if (s.kind == SegmentKind::line) {
    const Vec3 u = s.block.tangent_at(0.0);
    n.v_max = std::min(n.v_max, along(limits_.velocity, u));
    n.path_accel = options_.rule == CornerRule::paper ? amin : along(limits_.acceleration, u);
    n.path_jerk = jerk ? along(limits_.jerk, u) : inf;
    return;
  }
  const Vec3& U = n.tangent_bound;
  const Vec3& K = n.curvature_bound;
  if (!jerk) {
    // the per-axis box: |u_i|·v ≤ V_i and K_i·v² ≤ A_i (the tangential share is set per speed)
    // (the smallest root is the root of the smallest ratio: sqrt is monotone and correctly rounded)
    n.bound = SpeedBound::axis_box;
    n.path_jerk = inf;
    double wk = inf;
    for (int i = 0; i < 3; ++i) {
      if (U[i] > 0) n.v_max = std::min(n.v_max, limits_.velocity[i] / U[i]);
      if (K[i] > 0) wk = std::min(wk, limits_.acceleration[i] / K[i]);
    }
    if (wk < inf) n.v_max = std::min(n.v_max, std::sqrt(wk));
    n.path_accel = amin;
    return;
  }
  // with jerk limits: centripetal share c·A, tangential share sqrt(1 − c²)·A (vector bound)
  const double c = options_.centripetal_fraction;
  const double k = std::max(s.curvature, 1e-300);
  n.path_accel = std::sqrt(1.0 - c * c) * amin;
  n.v_max = std::min({n.v_max, vmin, std::sqrt(c * amin / k)});
  // jerk vector = (j_t − v³κ²) t + (3 v a_t κ + v³ dκ/ds) n: give j_t 0.4 J and the rest 0.3 J each
  n.path_jerk = 0.4 * jmin;
  n.v_max = std::min(n.v_max, 0.3 * jmin / (k * (c * amin + 3.0 * n.path_accel)));
  if (s.curvature_rate > 0) n.v_max = std::min(n.v_max, std::cbrt(0.3 * jmin / s.curvature_rate));
}

namespace {
// Reach coefficients of the axis box with per-axis terms U, K over a length L, from w0 to w (the
// larger squared speed, a = (w − w0)/(2L)): U_i·a + K_i·v² ≤ A_i at the worst speed of the ramp, w
// when K_i ≥ 0: w·(U_i + 2·L·K_i) ≤ U_i·w0 + 2·L·A_i; w0 when K_i < 0: w·U_i ≤ (U_i − 2·L·K_i)·w0 + 2·L·A_i.
void box_reach(double L, const Vec3& U, const Vec3& K, const Vec3& A, double (&alpha)[3], double (&beta)[3]) noexcept {
  double den[3], an[3];
  for (int i = 0; i < 3; ++i) {
    den[i] = K[i] >= 0 ? U[i] + 2.0 * L * K[i] : U[i];
    an[i] = K[i] >= 0 ? U[i] : U[i] - 2.0 * L * K[i];
  }
  const bool any = den[0] > 0 || den[1] > 0 || den[2] > 0;
  if (den[0] > 0 && den[1] > 0 && den[2] > 0) {
    // the three reciprocals from one division: 1/d0 = d1·d2/(d0·d1·d2), ...
    const double d01 = den[0] * den[1], r = 1.0 / (d01 * den[2]);
    const double rd[3] = {den[1] * den[2] * r, den[0] * den[2] * r, d01 * r};
    for (int i = 0; i < 3; ++i) {
      alpha[i] = an[i] * rd[i];
      beta[i] = 2.0 * L * A[i] * rd[i];
    }
  } else {
    for (int i = 0; i < 3; ++i) {
      if (den[i] > 0) {
        const double r = 1.0 / den[i];
        alpha[i] = an[i] * r;
        beta[i] = 2.0 * L * A[i] * r;
      } else {
        alpha[i] = 0.0;
        beta[i] = std::numeric_limits<double>::infinity();
      }
    }
  }
  if (!any) {  // no bound at all: the speed carries over
    alpha[0] = 1.0;
    beta[0] = 0.0;
  }
}

// box_reach() for both directions at once when every denominator of both is > 0 (the common case),
// as pairs (speeding up, slowing down) per axis, and without branches: den = U + 2L·max(K, 0) and
// an = U − 2L·min(K, 0) are box_reach()'s U + 2L·K or U (K ≥ 0), U or U − 2L·K (K < 0), since adding
// or subtracting a zero product leaves U ≥ 0 as it is. The same values. Returns false (nothing
// written) otherwise.
bool box_reach_both(double L, const Vec3 (&U)[2], const Vec3 (&K)[2], const Vec3& A, PassRecord& x) noexcept {
  using Pair = Eigen::Array2d;
  Pair den[3], an[3];
  const double L2 = 2.0 * L;
  for (int i = 0; i < 3; ++i) {
    const Pair u(U[0][i], U[1][i]), k(K[0][i], K[1][i]);
    den[i] = u + L2 * k.max(0.0);
    an[i] = u - L2 * k.min(0.0);
  }
  if (!((den[0] > 0.0) && (den[1] > 0.0) && (den[2] > 0.0)).all()) return false;
  const Pair d01 = den[0] * den[1], r = 1.0 / (d01 * den[2]);
  const Pair rd[3] = {den[1] * den[2] * r, den[0] * den[2] * r, d01 * r};
  for (int i = 0; i < 3; ++i) {
    const Pair alpha = an[i] * rd[i], beta = (2.0 * L * A[i]) * rd[i];
    x.alpha[i] = alpha[0];
    x.alpha_down[i] = alpha[1];
    x.beta[i] = beta[0];
    x.beta_down[i] = beta[1];
  }
  return true;
}
}  // namespace

void PlannerState::set_reach(PassRecord& x, const Node& n) const noexcept {
  x.bound = n.bound;
  if (n.bound == SpeedBound::path) {
    x.alpha[0] = x.alpha_down[0] = 1.0;
    x.beta[0] = x.beta_down[0] = 2.0 * x.path_accel * x.length;
    for (int i = 1; i < 3; ++i) {
      x.alpha[i] = x.alpha_down[i] = 0.0;
      x.beta[i] = x.beta_down[i] = inf;
    }
    return;
  }
  set_box_reach(x, n.ramp_tangent, n.ramp_curvature);
}

void PlannerState::set_box_reach(PassRecord& x, const Vec3 (&U)[2], const Vec3 (&K)[2]) const noexcept {
  x.bound = SpeedBound::axis_box;
  // speeding up: the forward reach; slowing down: the backward pass
  if (!box_reach_both(x.length, U, K, limits_.acceleration, x)) {
    box_reach(x.length, U[0], K[0], limits_.acceleration, x.alpha, x.beta);
    box_reach(x.length, U[1], K[1], limits_.acceleration, x.alpha_down, x.beta_down);
  }
}

// Arcs are cut into pieces of at most arc_piece_angle, each with its own bounds (the axis box is much
// tighter on a short piece); the pieces after the first are appended. Cubic blocks:
// split_cubic_block() (planner_cubic.cpp).
void PlannerState::split_last_block() noexcept {
  Node& p = node(tail_ - 1);
  if (p.extent == Extent::settled) return;
  p.extent = Extent::settled;
  if (p.segment.kind == SegmentKind::blend) {  // a cubic block (blend pieces are settled)
    split_cubic_block();
    return;
  }
  if (p.segment.kind != SegmentKind::arc) {
    update_pass(tail_ - 1);
    return;
  }
  const Node whole = p;
  const PieceBase base(whole);
  const double s0 = whole.segment.trim_start, s1 = whole.segment.full_length - whole.segment.trim_end;
  const int m = arc_piece_count(whole.segment);
  double v_prev = 0;
  for (int k = 0; k < m; ++k) {
    Node x = whole;
    const double a = s0 + (s1 - s0) * k / m, b = k + 1 == m ? s1 : s0 + (s1 - s0) * (k + 1) / m;
    x.segment.trim_start = a;
    x.segment.trim_end = whole.segment.full_length - b;
    arc_bounds(x.segment, a, b, x.tangent_bound, x.curvature_bound, x.ramp_tangent, x.ramp_curvature);
    finish_piece(x, base, k, m, v_prev);
    if (k == 0) {
      p = x;
      update_pass(tail_ - 1);
    } else {
      append(x);
    }
  }
}

void PlannerState::finish_piece(Node& x, const PieceBase& base, int k, int m, double& v_prev,
                                const AxisMinima* minima) noexcept {
  x.v_max = base.feed_cap;
  set_limits(x, nullptr, minima);
  x.start.curvature_step = x.end.curvature_step = false;  // set_limits gave the piece its full jerk again
  if (k == 0 && base.start.curvature_step) mark_curvature_step(x, true);
  if (k + 1 == m && base.end.curvature_step) mark_curvature_step(x, false);
  x.start.window = k == 0 ? base.start.window : 0.0;
  x.start.velocity_jump = k == 0 && base.start.velocity_jump;
  x.end.window = k + 1 == m ? base.end.window : 0.0;
  x.end.velocity_jump = k + 1 == m && base.end.velocity_jump;
  x.v_junction = k == 0 ? std::min(base.v_corner, x.v_max) : std::min(v_prev, x.v_max);
  v_prev = x.v_max;
}

void PlannerState::mark_curvature_step(Node& n, bool at_start) noexcept {
  if (!n.start.curvature_step && !n.end.curvature_step) n.path_jerk *= 0.5;
  (at_start ? n.start.curvature_step : n.end.curvature_step) = true;
}

double PlannerState::curvature_step_speed(const Vec3& dk) const noexcept {
  double v = inf;
  for (int i = 0; i < 3; ++i)
    if (std::abs(dk[i]) > 1e-12) v = std::min(v, std::sqrt(0.5 * limits_.jerk[i] * options_.ts2 / std::abs(dk[i])));
  return v;
}

}  // namespace netshape::motion::detail
