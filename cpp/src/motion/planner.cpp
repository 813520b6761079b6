#include "netshape/motion/planner.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "netshape/motion/corner.hpp"

namespace netshape::motion {

namespace {
constexpr double inf = std::numeric_limits<double>::infinity();
constexpr double tangent_angle = 1e-6;  // [rad] below this a junction counts as tangent

bool finite3(const Vec3& v) { return std::isfinite(v[0]) && std::isfinite(v[1]) && std::isfinite(v[2]); }

double min_over(const Vec3& per_axis, const Vec3& moving) {
  double m = inf;
  for (int i = 0; i < 3; ++i)
    if (moving[i] > 0) m = std::min(m, per_axis[i]);
  return std::isfinite(m) ? m : per_axis.minCoeff();
}

Vec3 end_tangent(const Segment& s) {
  return s.kind == SegmentKind::blend ? Vec3((s.ctrl[3] - s.ctrl[2]).normalized()) : s.block.tangent_at(1.0);
}
Vec3 start_tangent(const Segment& s) {
  return s.kind == SegmentKind::blend ? Vec3((s.ctrl[1] - s.ctrl[0]).normalized()) : s.block.tangent_at(0.0);
}
// point and tangent at arc length s along the untrimmed programmed piece
Vec3 piece_point(const Segment& s, double at) {
  if (s.kind == SegmentKind::line)
    return s.block.start + (at / s.full_length) * (s.block.end - s.block.start);
  return s.block.point_at(std::clamp(at / s.full_length, 0.0, 1.0));
}
Vec3 piece_tangent(const Segment& s, double at) { return s.block.tangent_at(std::clamp(at / s.full_length, 0.0, 1.0)); }
}  // namespace

Planner::Planner(const AxisLimits& limits, const PlanOptions& options) : limits_(limits), opt_(options) {
  limits_.validate();
  opt_.validate();
  const long per = opt_.rule == CornerRule::blend ? 5 : 1;
  cap_ = per * opt_.lookahead + 3;
  ring_.resize(static_cast<std::size_t>(cap_));
  quick_.resize(static_cast<std::size_t>(cap_));
}

void Planner::sync(long k) noexcept {
  const Node& n = at(k);
  Quick& x = q(k);
  x.v_lim = n.v_lim;
  x.len = plan_length(n);
  x.a = n.a;
  x.j = n.j;
}

void Planner::reset() noexcept {
  head_ = frozen_ = tail_ = 0;
  finished_ = done_ = false;
  pushed_ = 0;
  sample_ = 0;
  t_frozen_end_ = v_frozen_end_ = 0;
  have_last_ = false;
  last_point_ = Vec3::Zero();
  error_ = "";
}

int Planner::free_blocks() const noexcept {
  const long per = opt_.rule == CornerRule::blend ? 5 : 1;
  return static_cast<int>(std::max(0L, (cap_ - (tail_ - head_)) / per));
}

double Planner::end_time() const noexcept {
  return (finished_ && frozen_ == tail_) ? t_frozen_end_ : -1.0;
}

Status Planner::fail(const char* msg) noexcept {
  error_ = msg;
  return Status::invalid_input;
}

bool Planner::buffer_ready() const noexcept {
  const long per = opt_.rule == CornerRule::blend ? 5 : 1;
  return finished_ || cap_ - (tail_ - head_) < per;
}

double Planner::plan_length(const Node& n) const noexcept {
  const Segment& s = n.seg;
  const double te = n.tail_trim ? 0.45 * s.full_length : s.trim_end;
  return std::max(0.0, s.full_length - s.trim_start - te - n.res_s - n.res_e);
}

void Planner::set_params(Node& n) const noexcept {
  // n.vmax holds the programmed feed cap on entry
  const Segment& s = n.seg;
  const Vec3 moving = s.moving_axes();
  const double amin = min_over(limits_.acceleration, moving);
  const double vmin = min_over(limits_.velocity, moving);
  const double jmin = min_over(limits_.jerk, moving);
  const double c = opt_.centripetal_fraction;
  const bool jerk = std::isfinite(jmin);
  if (s.kind == SegmentKind::line) {
    const Vec3 u = s.block.tangent_at(0.0);
    n.vmax = std::min(n.vmax, along(limits_.velocity, u));
    n.a = opt_.rule == CornerRule::paper ? amin : along(limits_.acceleration, u);
    n.j = jerk ? along(limits_.jerk, u) : inf;
    return;
  }
  // arcs and blends: centripetal share c·A, tangential share sqrt(1 − c²)·A
  const double k = std::max(s.curvature, 1e-300);
  n.a = std::sqrt(1.0 - c * c) * amin;
  n.vmax = std::min({n.vmax, vmin, std::sqrt(c * amin / k)});
  n.j = inf;
  if (jerk) {
    // jerk vector = (j_t − v³κ²) t + (3 v a_t κ + v³ dκ/ds) n: give j_t 0.4 J and the rest 0.3 J each
    n.j = 0.4 * jmin;
    n.vmax = std::min(n.vmax, 0.3 * jmin / (k * (c * amin + 3.0 * n.a)));
    if (s.curvature_rate > 0) n.vmax = std::min(n.vmax, std::cbrt(0.3 * jmin / s.curvature_rate));
  }
}

Status Planner::push(const toolpath::Block& b) noexcept {
  if (finished_) return fail("push() after finish()");
  if (!finite3(b.start) || !finite3(b.end) || !finite3(b.center) || !std::isfinite(b.feed) || b.feed < 0)
    return fail("block has a non-finite coordinate or a negative feed");
  const long per = opt_.rule == CornerRule::blend ? 5 : 1;
  if (cap_ - (tail_ - head_) < per) return Status::buffer_full;
  const bool arc = b.kind == toolpath::MotionKind::arc;
  if (arc && !(b.radius() > 0)) return fail("arc radius must be positive");
  if (arc && b.turns < 1) return fail("arc turns must be at least 1");
  const double len = b.length();
  if (!(len > 1e-9)) return Status::ok;  // nothing to move
  if (have_last_ && (b.start - last_point_).norm() > 1e-6 * (1.0 + last_point_.norm()))
    return fail("block does not start where the previous one ended");
  const long source = pushed_++;
  Segment seg = arc ? Segment::arc(b, source) : Segment::line(b, source);
  last_point_ = b.end;
  have_last_ = true;
  const bool rapid = b.kind == toolpath::MotionKind::rapid;
  const double feed_cap = (rapid || b.feed <= 0) ? inf : b.feed;

  const bool has_prev = tail_ > head_ && tail_ - 1 >= frozen_;
  const long prev_index = tail_ - 1;
  const double ts2 = opt_.ts2;
  const bool jump_rule = opt_.rule == CornerRule::vector || opt_.rule == CornerRule::per_axis;

  // the new node (not yet in the ring)
  Node nn;
  nn.seg = seg;
  nn.vmax = feed_cap;
  set_params(nn);
  if (jump_rule) nn.res_e = 2.0 * ts2 * std::min(nn.vmax, seg.full_length / (8.0 * ts2));
  nn.tail_trim = opt_.rule == CornerRule::blend;

  if (!has_prev) {
    nn.v_lim = 0.0;  // start from rest
    at(tail_) = nn;
    sync(tail_);
    q(tail_).vb = 0.0;
    ++tail_;
    back_pass(tail_ - 1);
    return Status::ok;
  }
  Node& p = at(prev_index);
  const Vec3 u1 = end_tangent(p.seg), u2 = start_tangent(seg);
  const double theta = turn_angle(u1, u2);
  const double vcap = std::min(p.vmax, nn.vmax);
  const double amin = moving_axes_min(limits_.acceleration, u1, u2);
  const bool arc_adjacent = p.seg.kind == SegmentKind::arc || seg.kind == SegmentKind::arc;
  const double f = arc_adjacent ? 1.0 - opt_.centripetal_fraction : 1.0;

  if (opt_.rule == CornerRule::blend && theta > tangent_angle && theta < pi - 1e-3) {
    // corner blend: P0 on the previous piece, P3 on the next, both at distance d from the vertex
    const double dmax = 0.45 * std::min(p.seg.full_length, seg.full_length);
    double d = std::min(dmax, 4.0 * opt_.tolerance / std::sin(0.5 * theta));
    std::array<Vec3, 4> bl;
    for (int it = 0; it < 40; ++it) {
      const double sp = p.seg.full_length - d;
      const Vec3 p0 = piece_point(p.seg, sp), t0 = piece_tangent(p.seg, sp);
      const Vec3 p3 = piece_point(seg, d), t3 = piece_tangent(seg, d);
      bl = {p0, p0 + d * t0, p3 - d * t3, p3};
      if (p.seg.kind == SegmentKind::line && seg.kind == SegmentKind::line) break;  // bound is exact
      double dev = 0;
      for (int i = 1; i < 16; ++i) {
        const Vec3 q = bezier_point(bl, i / 16.0);
        dev = std::max(dev, std::min(p.seg.distance_to_piece(q, sp, p.seg.full_length),
                                     seg.distance_to_piece(q, 0.0, d)));
      }
      if (dev <= opt_.tolerance) break;
      d *= 0.5;
    }
    p.seg.trim_end = d;
    p.tail_trim = false;
    nn.seg.trim_start = d;
    // four pieces (de Casteljau at u = 1/4, 1/2, 3/4), each driven at the speed of its own largest
    // curvature: the speed dips only where the curvature peaks
    std::array<std::array<Vec3, 4>, 4> pieces;
    {
      auto split = [](const std::array<Vec3, 4>& c, std::array<Vec3, 4>& l, std::array<Vec3, 4>& r) {
        const Vec3 a = 0.5 * (c[0] + c[1]), b = 0.5 * (c[1] + c[2]), e = 0.5 * (c[2] + c[3]);
        const Vec3 ab = 0.5 * (a + b), be = 0.5 * (b + e), m = 0.5 * (ab + be);
        l = {c[0], a, ab, m};
        r = {m, be, e, c[3]};
      };
      std::array<Vec3, 4> h0, h1;
      split(bl, h0, h1);
      split(h0, pieces[0], pieces[1]);
      split(h1, pieces[2], pieces[3]);
    }
    const double vfeed = std::min(p.vmax, nn.vmax);
    double v_prev = p.vmax;
    for (const auto& c : pieces) {
      Node bn;
      bn.seg = Segment::blend(c[0], c[1], c[2], c[3], p.seg.source);
      bn.vmax = vfeed;
      set_params(bn);
      bn.v_lim = std::min(v_prev, bn.vmax);
      v_prev = bn.vmax;
      at(tail_) = bn;
      sync(tail_);
      q(tail_).vb = 0.0;
      ++tail_;
    }
    nn.v_lim = std::min(v_prev, nn.vmax);
    at(tail_) = nn;
    sync(tail_);
    q(tail_).vb = 0.0;
    ++tail_;
    sync(prev_index);
    back_pass(prev_index);
    return Status::ok;
  }

  double v = vcap;
  bool jump = false;
  if (theta > tangent_angle) {
    switch (opt_.rule) {
      case CornerRule::paper:
        v = std::max(paper_corner_speed(amin, opt_.ts1, theta), opt_.allowable_speed_difference);
        break;
      case CornerRule::vector:
        v = f * vector_corner_speed(u1, u2, amin, ts2);
        jump = true;
        break;
      case CornerRule::per_axis:
        v = f * per_axis_corner_speed(u1, u2, limits_.acceleration, ts2);
        jump = true;
        break;
      case CornerRule::junction_deviation: {
        const double dev = opt_.square_corner_velocity > 0
                               ? klipper_junction_deviation(opt_.square_corner_velocity, amin)
                               : opt_.junction_deviation;
        v = junction_deviation_speed(amin, dev, theta);
        break;
      }
      case CornerRule::blend: v = 0.0; break;  // reversal: stop
    }
    v = std::min(v, vcap);
  }
  if (jump_rule) {
    if (jump) {
      v = std::min({v, (p.seg.full_length - p.seg.trim_start) / (8.0 * ts2), seg.full_length / (8.0 * ts2)});
      p.res_e = 2.0 * ts2 * v;
      nn.res_s = 2.0 * ts2 * v;
    } else {
      p.res_e = 0.0;
    }
    p.jump_e = jump;
    nn.jump_s = jump;
  }
  nn.v_lim = v;
  at(tail_) = nn;
  sync(tail_);
  q(tail_).vb = 0.0;
  ++tail_;
  sync(prev_index);
  back_pass(prev_index);
  return Status::ok;
}

void Planner::finish() noexcept {
  if (finished_) return;
  finished_ = true;
  if (tail_ > frozen_) {
    Node& t = at(tail_ - 1);
    t.tail_trim = false;
    t.seg.trim_end = 0.0;
    t.res_e = 0.0;
    t.jump_e = false;
    sync(tail_ - 1);
    back_pass(tail_ - 1);
  }
}

void Planner::back_pass(long dirty_from) noexcept {
  double v_next = 0.0;  // the buffer always ends at rest
  for (long k = tail_ - 1; k >= frozen_; --k) {
    Quick& n = q(k);
    // seeds/002 eq. 3 (trapezoid) or its S-curve counterpart, capped by the junction limit
    const double reach = std::isfinite(n.j) ? reach_speed(v_next, n.len, n.a, n.j)
                                            : std::sqrt(v_next * v_next + 2.0 * n.a * n.len);
    const double v = std::min(n.v_lim, reach);
    if (k < dirty_from && v == n.vb) break;  // nothing changes further back
    n.vb = v;
    v_next = v;
  }
}

bool Planner::freeze_next() noexcept {
  if (frozen_ >= tail_) return false;
  const bool is_tail = frozen_ == tail_ - 1;
  if (is_tail && !finished_) return false;
  if (!buffer_ready()) return false;
  Node& n = at(frozen_);
  const double vs = v_frozen_end_;
  const double target = is_tail ? 0.0 : q(frozen_ + 1).vb;
  const double ve = std::min(target, reach_speed(vs, plan_length(n), n.a, n.j));
  n.prof = Profile::make(n.seg.length(), vs, ve, std::max(n.vmax, std::max(vs, ve)), n.a, n.j,
                         n.jump_s ? 2.0 * opt_.ts2 * vs : 0.0, n.jump_e ? 2.0 * opt_.ts2 * ve : 0.0);
  n.t0 = t_frozen_end_;
  t_frozen_end_ += n.prof.duration;
  v_frozen_end_ = ve;
  ++frozen_;
  return true;
}

Status Planner::ensure_frozen_until(double t) noexcept {
  while (t_frozen_end_ <= t && frozen_ < tail_) {
    if (!freeze_next()) return Status::need_blocks;
  }
  if (t_frozen_end_ <= t && !finished_) return Status::need_blocks;
  return Status::ok;
}

Status Planner::next(Sample& out) noexcept {
  if (done_) return Status::finished;
  const double ts2 = opt_.ts2;
  const double t = static_cast<double>(sample_) * ts2;
  if (sample_ % opt_.fine_steps() == 0) {
    // rough loop: freeze the profile for the coming rough period [t, t + ts1] if the buffer allows
    const Status st = ensure_frozen_until(t + opt_.ts1);
    if (st != Status::ok && t_frozen_end_ <= t) return st;
  }
  {
    const Status st = ensure_frozen_until(t);
    if (st != Status::ok) return st;
  }
  out.t = t;
  if (finished_ && frozen_ == tail_ && t >= t_frozen_end_) {
    // past the end: the program's end point at rest
    out.position = last_point_;
    out.velocity.setZero();
    out.feed = 0;
    out.path_acceleration = 0;
    out.block = pushed_ - 1;
    done_ = true;
    head_ = tail_;
    ++sample_;
    return Status::ok;
  }
  while (head_ < frozen_ - 1 && at(head_).t0 + at(head_).prof.duration <= t) ++head_;
  const Node& n = at(head_);
  double s, v, acc;
  n.prof.eval(t - n.t0, s, v, acc);
  out.position = n.seg.point_at(s);
  out.velocity = v * n.seg.tangent_at(s);
  out.feed = v;
  out.path_acceleration = acc;
  out.block = n.seg.source;
  ++sample_;
  return Status::ok;
}

Status Planner::next_segment(PlannedSegment& out) noexcept {
  if (head_ == frozen_) {
    if (frozen_ == tail_) return finished_ ? Status::finished : Status::need_blocks;
    if (!freeze_next()) return Status::need_blocks;
  }
  const Node& n = at(head_);
  out.segment = n.seg;
  out.profile = n.prof;
  out.t0 = n.t0;
  ++head_;
  return Status::ok;
}

}  // namespace netshape::motion
