// The look-ahead over the ring: the backward pass (Lee & Lee eq. 3, 5 in squared speeds) and the
// freeze of the next segment's profile once the buffer is deep enough.
#include <algorithm>
#include <cmath>

#include "motion/planner/state.hpp"

namespace netshape::motion::detail {

inline double PlannerState::reach_squared(const PassRecord& n, double w0) const noexcept {
  if (std::isfinite(n.path_jerk)) {
    const double r = reach_speed(std::sqrt(w0), n.length, n.path_accel, n.path_jerk);
    return r * r;
  }
  return std::min({n.alpha[0] * w0 + n.beta[0], n.alpha[1] * w0 + n.beta[1], n.alpha[2] * w0 + n.beta[2]});
}

// Jerk-limited backward step: the largest squared start speed from which the node slows down to any
// end speed from sqrt(w_next) up (reach_back_speed: monotone in w_next although one S-curve ramp's
// distance is not, so the start speed promised to the node before stays feasible when w_next rises).
inline double reach_back_squared(const PassRecord& n, double w_next) noexcept {
  const double r = reach_back_speed(std::sqrt(w_next), n.length, n.path_accel, n.path_jerk);
  return r * r;
}

namespace {
// The backward steps over the pieces of a cubic record from the last to the first (the step of a node
// without jerk limits, the only mode with cubic records) from w, the squared speed after the record;
// returns the squared speed before it, with each piece's into wb[p] when `store`. Only the N axes of
// r.live_down_axis (the others never bind: the minimum is the same, and so are its bits, the values
// being ≥ 0).
template <int N, bool store>
inline double cubic_chain(const CubicRecord& r, double w, double* wb) noexcept {
  const double* al[3] = {nullptr, nullptr, nullptr};
  const double* be[3] = {nullptr, nullptr, nullptr};
  for (int j = 0; j < N; ++j) {
    al[j] = r.alpha_down[r.live_down_axis[j]];
    be[j] = r.beta_down[r.live_down_axis[j]];
  }
#if defined(__GNUC__)
#pragma GCC unroll 4  // (a step is ~8 instructions: the loop's own 3 are a third of it)
#endif
  for (int p = r.np - 1; p >= 0; --p) {
    if constexpr (N == 3) {
      w = min_of(min_of(r.w_junction[p], al[0][p] * w + be[0][p]), min_of(al[1][p] * w + be[1][p], al[2][p] * w + be[2][p]));
    } else if constexpr (N == 2) {
      w = min_of(min_of(r.w_junction[p], al[0][p] * w + be[0][p]), al[1][p] * w + be[1][p]);
    } else if constexpr (N == 1) {
      w = min_of(r.w_junction[p], al[0][p] * w + be[0][p]);
    } else {
      w = r.w_junction[p];
    }
    if constexpr (store) wb[p] = w;
  }
  return w;
}
template <bool store>
inline double cubic_chain(const CubicRecord& r, double w, double* wb) noexcept {
  switch (r.live_down) {
    case 3: return cubic_chain<3, store>(r, w, wb);
    case 2: return cubic_chain<2, store>(r, w, wb);
    case 1: return cubic_chain<1, store>(r, w, wb);
    default: return cubic_chain<0, store>(r, w, wb);
  }
}

// Backward-pass steps over the nodes k = hi, hi − 1, ..., lo (ring records rec, slot k & mask):
// w_next becomes each node's new squared speed, min(junction limit, reach(node, w_next)); a line-blend
// or cubic-record node runs over its pieces (line_blends, cubics). With stop_if_same the steps stop at
// the first node whose value stays (returning false). The mode and the stop test are template
// parameters, so the loop of the common case (no jerk limits, nodes that changed) carries neither.
template <bool stop_if_same, class Reach>
inline bool back_steps(PassRecord* rec, std::size_t mask, LineBlendRecord* line_blends, CubicRecord* cubics, long hi,
                       long lo, double& w_next, const Reach& reach) noexcept {
  for (long k = hi; k >= lo; --k) {
    PassRecord& n = rec[static_cast<std::size_t>(k) & mask];
    double w;
    if (n.line_blend >= 0) {
      // a line-blend node: its pieces from the last to the first
      LineBlendRecord& r = line_blends[static_cast<std::size_t>(n.line_blend)];
      w = w_next;
      for (int p = r.np - 1; p >= 0; --p) {
        w = min_of(min_of(r.w_junction[p], r.alpha[0][p] * w + r.beta[0][p]),
                   min_of(r.alpha[1][p] * w + r.beta[1][p], r.alpha[2][p] * w + r.beta[2][p]));
        if (stop_if_same && w == r.w_backward[p]) {  // so are the pieces before it (and w == n.w_backward below)
          w = r.w_backward[0];
          break;
        }
        r.w_backward[p] = w;
      }
    } else if (n.cubic >= 0) {
      // a cubic-record node: its pieces from the last to the first, each as a node of its own; what
      // it carries back depends on what comes after it alone
      CubicRecord& r = cubics[static_cast<std::size_t>(n.cubic)];
      if (stop_if_same && w_next == r.w_after) return false;  // nothing changes here or further back
      r.w_after = w_next;
      w = cubic_chain<false>(r, w_next, nullptr);
    } else {
      w = reach(n, w_next);
    }
    if (stop_if_same && w == n.w_backward) return false;  // nothing changes further back
    n.w_backward = w;
    w_next = w;
  }
  return true;
}
}  // namespace

// From the tail (which ends at rest) back to the frozen prefix: each node's backward squared speed is
// the smallest of its junction limit and what it reaches from the next node's. Nodes before
// dirty_from did not change themselves, so the pass stops at the first of them whose value stays.
void PlannerState::back_pass(long dirty_from) noexcept {
  if (tail_ <= frozen_) return;
  PassRecord* const rec = passes_.data();
  LineBlendRecord* const lb = line_blends_.data();
  CubicRecord* const cr = cubic_records_.data();
  const std::size_t mask = ring_mask_;
  const long changed_end = std::clamp(dirty_from, frozen_, tail_);  // nodes [changed_end, tail_) changed themselves
  double w_next = 0.0;  // the buffer always ends at rest (squared speeds: no root per node)
  const auto run = [&](const auto& reach) {
    back_steps<false>(rec, mask, lb, cr, tail_ - 1, changed_end, w_next, reach);
    back_steps<true>(rec, mask, lb, cr, changed_end - 1, frozen_, w_next, reach);
  };
  if (!jerk_limited_) {
    // Lee & Lee eq. 3 (trapezoid; on curves the axis box), capped by the junction limit: the min of
    // three affine terms (on a line alpha_down = (1, 0, 0), beta_down = (2·a·L, inf, inf): the first
    // term is 1·w + b = w + b exactly, the others +inf)
    run([](const PassRecord& n, double w) {
      return min_of(min_of(n.w_junction, n.alpha_down[0] * w + n.beta_down[0]),
                    min_of(n.alpha_down[1] * w + n.beta_down[1], n.alpha_down[2] * w + n.beta_down[2]));
    });
  } else {
    run([](const PassRecord& n, double w) { return std::min(n.w_junction, reach_back_squared(n, w)); });
  }
}

inline bool PlannerState::buffer_ready() const noexcept {
  // free_blocks() == 0 without its division
  return finished_ || capacity_ - (tail_ - head_) < nodes_per_push || blocks_in_buffer() >= options_.lookahead + 1;
}

// Peak speed and tangential acceleration from the axis box at that speed, one acceleration for both
// ramps (the smaller of the speeding-up and slowing-down terms' — a ramp the passes planned with the
// larger one is monotone, and Profile::make raises a to fit it):
// 2·w − vs² − ve² = 2·L·(A_i − K_i·w)/U_i for the binding term; a term with K_i < 0 is worst at the
// lowest speed of the profile, min(vs, ve): A_i − K_i·min(vs², ve²) and K_i = 0 there.
inline Profile PlannerState::axis_box_profile(double len, double vs, double ve, double v_max,
                                              const Vec3 (&ramp_tangent)[2], const Vec3 (&ramp_curvature)[2], double ws,
                                              double we) const noexcept {
  const double lr = std::max(0.0, len - std::min(ws, len) - std::min(we, len));
  const double S = vs * vs + ve * ve, wlow = std::min(vs * vs, ve * ve);
  // the six terms (speeding up x, y, z, slowing down x, y, z) as arrays, element by element the
  // scalar expressions (max / min against 0 as std::max / std::min; Eigen vectorises them)
  using Six = Eigen::Array<double, 6, 1>;
  static_assert(sizeof(ramp_tangent) == 6 * sizeof(double), "ramp terms are 6 packed doubles");
  const Eigen::Map<const Six> k(ramp_curvature[0].data()), U(ramp_tangent[0].data());
  const Six Ke = k.max(0.0);
  const Six Ae = acceleration2_ - k.min(0.0) * wlow;
  Six num = U * S + (2.0 * lr) * Ae;
  const Six den = 2.0 * U + (2.0 * lr) * Ke;
  double wp = std::min({v_max * v_max, min_ratio(num.data(), den.data()), min_ratio(num.data() + 3, den.data() + 3)});
  wp = std::max(wp, std::max(vs * vs, ve * ve));
  num = Ae - Ke * wp;
  double a = std::min(min_ratio(num.data(), U.data()), min_ratio(num.data() + 3, U.data() + 3));
  // at the curvature cap the tangential budget is 0: a floor of 1e-6·A keeps the rounding-size speed
  // differences of neighbouring pieces from turning into long ramps
  const double amin = limits_.acceleration.minCoeff();
  if (!(a > 1e-6 * amin)) a = 1e-6 * amin;
  if (!std::isfinite(a)) a = amin;
  return Profile::make(len, vs, ve, std::sqrt(wp), a, inf, ws, we);
}

// The profile of segment frozen_ from the end speed of the frozen prefix to the smaller of what the
// next segment allows (its backward speed) and what it reaches; only when the buffer is full or
// finished, and never the last segment before finish().
bool PlannerState::freeze_next() noexcept {
  if (frozen_ >= tail_) return false;
  const bool is_tail = frozen_ == tail_ - 1;
  if (is_tail && !finished_) return false;
  if (!buffer_ready()) return false;
  const std::size_t slot = ring_slot(frozen_);
  Node& n = nodes_[slot];
  const PassRecord& qn = passes_[slot];
  const double vs = v_frozen_end_;
  const double wt = is_tail ? 0.0 : passes_[(slot + 1) & ring_mask_].w_backward;
  if (qn.line_blend >= 0) {
    freeze_line_blend(n, line_blends_[static_cast<std::size_t>(qn.line_blend)], vs, wt);
    return true;
  }
  if (qn.cubic >= 0) {
    freeze_cubic_record(n, cubic_records_[static_cast<std::size_t>(qn.cubic)], vs, wt);
    return true;
  }
  const double ve = std::sqrt(std::min(wt, reach_squared(qn, vs * vs)));
  const double wf = window_periods();
  const double ws = n.start.velocity_jump ? wf * options_.ts2 * vs : 0.0;
  const double we = n.end.velocity_jump ? wf * options_.ts2 * ve : 0.0;
  const double len = n.segment.length();
  if (n.bound == SpeedBound::axis_box && !std::isfinite(qn.path_jerk)) {
    n.profile = axis_box_profile(len, vs, ve, n.v_max, n.ramp_tangent, n.ramp_curvature, ws, we);
  } else {
    n.profile = Profile::make(len, vs, ve, std::max(n.v_max, std::max(vs, ve)), n.path_accel, n.path_jerk, ws, we);
  }
  n.t0 = t_frozen_end_;
  t_frozen_end_ += n.profile.duration;
  v_frozen_end_ = ve;
  ++frozen_;
  return true;
}

// The pieces of a line-blend node one after the other (the freeze kernel, kernels/line_blend_kernels.hpp), as
// freeze_next() does for single nodes.
void PlannerState::freeze_line_blend(Node& n, LineBlendRecord& r, double vs, double wt) noexcept {
  const double v_end = line_blend_kernels_->freeze(r, vs, wt, limits_.acceleration, t_frozen_end_);
  freeze_record_node(n, vs, v_end, r.t0[r.np - 1] + r.dur[r.np - 1]);
}

// A node whose pieces live in a record (line blend, cubic) is frozen from vs to ve, its last piece
// ending at time t_end: of the node's profile only the end speeds and the duration are read (the
// pieces have their own); the frozen prefix moves past it.
void PlannerState::freeze_record_node(Node& n, double vs, double ve, double t_end) noexcept {
  n.profile.vs = vs;
  n.profile.ve = ve;
  n.profile.duration = t_end - t_frozen_end_;
  n.t0 = t_frozen_end_;
  t_frozen_end_ = t_end;
  v_frozen_end_ = ve;
  ++frozen_;
}

// The pieces of a cubic-record node one after the other, as freeze_next() freezes nodes: each piece's
// end speed is the smaller of the next piece's backward speed (of the next node: wt) and what it
// reaches from its start speed (a sequential chain); then every piece's profile, axis_box_profile()
// without windows, in the cubic-record kernel (all pieces at once, the same operations element by
// element).
void PlannerState::freeze_cubic_record(Node& n, CubicRecord& r, double vs, double wt) noexcept {
  const int np = r.np;
  double wb[CubicRecord::pieces];  // the pieces' backward squared speeds, as the backward pass found them
  cubic_chain<true>(r, r.w_after, wb);
  double v = vs;
  for (int k = 0; k < np; ++k) {
    const double w_end = k + 1 < np ? wb[k + 1] : wt;
    const double w0 = v * v;  // reach_squared() without jerk limits
    const double reach = min_of(min_of(r.alpha[0][k] * w0 + r.beta[0][k], r.alpha[1][k] * w0 + r.beta[1][k]),
                                r.alpha[2][k] * w0 + r.beta[2][k]);  // (std::min of the three)
    r.vs[k] = v;
    v = std::sqrt(std::min(w_end, reach));
    r.ve[k] = v;
  }
  cubic_record_kernels_->freeze(r, limits_.acceleration.data(), limits_.acceleration.minCoeff());
  double t = t_frozen_end_;
  for (int k = 0; k < np; ++k) {
    r.t0[k] = t;
    t += r.dur[k];
  }
  r.cursor = 0;
  freeze_record_node(n, vs, v, t);
}

}  // namespace netshape::motion::detail
