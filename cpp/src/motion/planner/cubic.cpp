// Cubic blocks (cubic.hpp) in the planner: their validation, the whole-block node (the Bézier with its
// arc-length table, bounds over all of it), the cut into pieces at table nodes once the block's end is
// known (per-axis bounds per piece, as the corner blends' pieces; without jerk limits the pieces are
// arrays in one record behind one ring node), and the test for a curvature-continuous joint. push()
// (planner/push.cpp) sets their junctions like any block's.
#include <algorithm>
#include <array>
#include <cmath>

#include "motion/planner/blend_bounds.hpp"
#include "motion/planner/geometry.hpp"
#include "motion/planner/state.hpp"

namespace netshape::motion::detail {

namespace {
// index of the table interval holding arc length s (from the untrimmed start), 0..15
int interval_at(const std::array<double, 17>& table, double s) {
  const auto it = std::upper_bound(table.begin(), table.end(), s);
  return std::clamp(static_cast<int>(it - table.begin()) - 1, 0, 15);
}

// Whether pieces of two table intervals each lose little against pieces of one (curvature: |κ| at the
// 17 table nodes; share: the centripetal part of the axis budget at the cubic's fastest speed, as in
// split_cubic_block()): over every pair of intervals the tangent turns by at most 0.05 rad (the largest
// |κ| at its three nodes times its length), so no axis' tangent bound grows by more than 0.05 of the
// speed; and the centripetal part takes at most twice the budget, or |κ| varies by at most 3 % over each
// pair, so the merged curvature bound hardly binds or hardly differs. A small cubic of a smoothed
// micro-segment program (~0.5 mm) mostly qualifies; a quarter circle in one cubic turns 0.2 rad per
// pair and keeps 16 pieces.
bool pairs_suffice(const double (&curvature)[17], const std::array<double, 17>& table, double share) {
  bool even = true;
  for (int j = 0; j < 16; j += 2) {
    const double lo = std::min({curvature[j], curvature[j + 1], curvature[j + 2]});
    const double hi = std::max({curvature[j], curvature[j + 1], curvature[j + 2]});
    if (!(hi * (table[static_cast<std::size_t>(j + 2)] - table[static_cast<std::size_t>(j)]) <= 0.05)) return false;
    even = even && hi <= 1.03 * lo;
  }
  return even || share <= 2.0;
}
}  // namespace

const CubicRecordKernels& cubic_record_kernels_plain() { return baseline::cubic_record_kernel_table; }

const CubicRecordKernels& cubic_record_kernels() {
  static const CubicRecordKernels& chosen = NETSHAPE_SIMD_SELECT(detail, cubic_record_kernel_table);
  return chosen;
}

const char* PlannerState::cubic_error(const toolpath::Block& b, const CubicControls& c) noexcept {
  if (b.kind == toolpath::MotionKind::arc) return "cubic block: kind must be line (the chord P0 -> P3), got arc";
  if (b.kind == toolpath::MotionKind::rapid) return "cubic block: kind must be line (the chord P0 -> P3), got rapid";
  if (b.kind != toolpath::MotionKind::line) return "cubic block: kind must be line (the chord P0 -> P3)";
  if (!c.c1.allFinite()) return "cubic block: control point c1 (P1) has a non-finite coordinate";
  if (!c.c2.allFinite()) return "cubic block: control point c2 (P2) has a non-finite coordinate";
  return nullptr;
}

void PlannerState::init_cubic_node(Node& n, const toolpath::Block& b, const CubicControls& c, long source) noexcept {
  n = Node{};
  CubicTable& ct = cubic_table(source);
  Segment& s = n.segment;
  // Segment::blend(b.start, c.c1, c.c2, b.end, source) with its node frames straight into the table's
  // bounds (the cubic-record kernel); symmetric Béziers through Segment::blend itself
  s.kind = SegmentKind::blend;
  s.ctrl = {b.start, c.c1, c.c2, b.end};
  s.source = source;
  double folds[3][10], finish[2];
  if (cubic_record_kernels_->cubic_node(s.ctrl[0].data(), s.table.data(), ct.curvature, ct.bounds, folds, finish)) {
    if (finish[0] >= 0) {
      s.curvature = finish[0];
      s.curvature_rate = finish[1];
      s.full_length = s.table[16];
    } else {
      finish_blend(s, ct.curvature);
    }
    BlendBounds::whole_from(folds, n.tangent_bound, n.curvature_bound, n.ramp_tangent, n.ramp_curvature);
  } else {
    std::array<Vec3, 17> T, Kv;
    s = Segment::blend(b.start, c.c1, c.c2, b.end, source, &T, &Kv);
    cubic_record_kernels_->fill(ct.bounds, T[0].data(), Kv[0].data());
    for (std::size_t i = 0; i < 17; ++i) ct.curvature[i] = Kv[i].norm();
    ct.bounds.whole(n.tangent_bound, n.curvature_bound, n.ramp_tangent, n.ramp_curvature);
  }
  s.block = b;  // the chord (kind line) with the block's feed and line number
  ct.minima = axis_minima(s);
  n.geometry = Geometry::in_node;
}

// The trimmed window [a, b] of the cubic (blends at either end trim it) is cut at the table nodes
// every 16/cubic_piece_count() intervals that lie inside it (without jerk limits fewer for gentle
// cubics, below); a piece's bounds are those of the table
// intervals it touches (valid on any part of them, so on the trimmed end pieces too). In jerk mode
// each piece gets the largest curvature and |dκ/ds| at its table nodes, as the corner blends' pieces.
// Without jerk limits and windows (cubic_records_used()) the pieces go into the cubic record of the
// block and the whole-block node stays its one node (fill_cubic_record()). Else the whole-block node
// becomes the first piece; the others are written in place in the ring slots after it (free: push()
// keeps nodes_per_push of them), with every Node field the planner reads before the freeze set. The
// last piece holds the whole block's segment (push() and the blend rule read the curve at its end);
// the ones between keep only kind, trims, length, curvature and source (Geometry::in_cubic_store),
// the rest of the segment stays once in the cubic store.
void PlannerState::split_cubic_block() noexcept {
  const long k0 = tail_ - 1;
  Node& whole = node(k0);
  const PieceBase base(whole);
  const long block = whole.block;
  CubicTable& ct = cubic_table(block);  // from init_cubic_node (no other cubic of its parity since)
  BlendBounds& tab = ct.bounds;
  const Segment& g = whole.segment;  // (the first piece's below: its trims and curvature change)
  const double L = g.full_length, a = g.trim_start, b = L - g.trim_end;
  const double sliver = 1e-6 * L;  // cuts closer than this to a window end are dropped
  int step = 16 / cubic_piece_count();
  if (!jerk_limited_) {
    // a gentle cubic (the centripetal part takes at most 2 % of any axis' budget at the fastest speed
    // the tangent bounds allow) is one piece, a moderate one (at most 25 %) four, one whose table
    // intervals may go two at a time (pairs_suffice) eight: finer pieces would only relax a bound that
    // hardly binds or hardly changes between them, and each piece costs a node, its passes and a
    // planned segment
    const Vec3& U = whole.tangent_bound;  // the whole cubic's bounds (init_cubic_node)
    const Vec3& K = whole.curvature_bound;
    double vcap = base.feed_cap;
    for (int i = 0; i < 3; ++i)
      if (U[i] > 0) vcap = std::min(vcap, limits_.velocity[i] / U[i]);
    double share = 0;
    for (int i = 0; i < 3; ++i) share = std::max(share, K[i] * vcap * vcap / limits_.acceleration[i]);
    if (share <= 0.02) step = 16;
    else if (share <= 0.25) step = 4;
    else if (pairs_suffice(ct.curvature, g.table, share)) step = 2;
  }
  double cuts[18];  // the window's ends and at most 15 table nodes between them
  int node_at[18];  // the table node a cut lies on, −1 at the window's ends
  int nc = 0;
  node_at[nc] = -1;
  cuts[nc++] = a;
  for (int i = step; i < 16; i += step) {
    const double s = g.table[static_cast<std::size_t>(i)];
    if (s > a + sliver && s < b - sliver) {
      node_at[nc] = i;
      cuts[nc++] = s;
    }
  }
  node_at[nc] = -1;
  cuts[nc++] = b;
  const int m = nc - 1;
  const AxisMinima& minima = ct.minima;  // the same axes move on every piece
  // the pieces are single table intervals (but at trimmed ends); the cubic record takes them from the
  // kernel itself (fill_cubic_record)
  if (step == 1 && !cubic_records_used()) cubic_record_kernels_->singles(tab);
  // the intervals [i0, i1) that hold piece k, [cuts[k], cuts[k + 1]]: i0 is the interval holding its
  // start (interval_at), i1 the first table node at or past its end. A cut on table node i, where the
  // table (non-decreasing) rises on both sides of it, gives them without a search: interval_at(table[i])
  // = i when table[i + 1] > table[i], and the first node at or past table[i] is i when
  // table[i − 1] < table[i]
  const auto tab_at = [&g](int i) { return g.table[static_cast<std::size_t>(i)]; };
  const auto intervals = [&](int k, int& i0, int& i1) {
    const int n0 = node_at[k], n1 = node_at[k + 1];
    i0 = n0 > 0 && tab_at(n0 + 1) > tab_at(n0) ? n0 : interval_at(g.table, cuts[k]);
    const int first_at =
        n1 > 0 && tab_at(n1 - 1) < tab_at(n1)
            ? n1
            : static_cast<int>(std::lower_bound(g.table.begin(), g.table.end(), cuts[k + 1]) - g.table.begin());
    i1 = std::clamp(first_at, i0 + 1, 16);
  };
  if (cubic_records_used()) {
    fill_cubic_record(whole, base, cuts, m, step, minima.acceleration, intervals);
    return;
  }
  if (m > 2) cubics_[block_slot(block)] = g;
  double v_prev = 0;
  for (int k = 0; k < m; ++k) {
    Node& x = k == 0 ? whole : node(k0 + k);
    if (k + 1 == m && k > 0) {
      x.segment = g;
      x.geometry = Geometry::in_node;
    } else if (k > 0) {
      x.segment.kind = SegmentKind::blend;
      x.segment.full_length = L;
      x.segment.source = g.source;
      x.geometry = Geometry::in_cubic_store;
    }
    if (k > 0) {
      x.block = block;
      x.feed_cap = base.feed_cap;
      x.v_corner = base.v_corner;
    }
    x.segment.trim_start = cuts[k];
    x.segment.trim_end = L - cuts[k + 1];
    int i0, i1;
    intervals(k, i0, i1);
    if (step == 1 && i1 == i0 + 1) {
      tab.single(i0, x.tangent_bound, x.curvature_bound, x.ramp_tangent, x.ramp_curvature);
    } else {
      tab.bounds(i0, i1, x.tangent_bound, x.curvature_bound);
      tab.ramps(i0, i1, x.tangent_bound, x.curvature_bound, x.ramp_tangent, x.ramp_curvature);
    }
    piece_curvature(ct.curvature, g.table, i0, i1, x.segment.curvature, x.segment.curvature_rate);
    x.extent = Extent::settled;
    finish_piece(x, base, k, m, v_prev, &minima);
    update_pass(k0 + k);
    if (k > 0) pass(k0 + k).w_backward = 0.0;
  }
  tail_ = k0 + m;
}

// The pieces of the cubic block in node `whole` (its cuts, m pieces, table step as split_cubic_block())
// into the cubic record of its block, with what finish_piece(), set_limits() and update_pass() give a
// piece node of a curved block without jerk limits or windows; `whole` becomes the record's node. The
// bounds per piece as there; the caps and reach coefficients of all pieces at once in the cubic-record
// kernel (box_reach_both()'s where each of its denominators is > 0, else set_box_reach() for that piece
// alone).
template <class Intervals>
void PlannerState::fill_cubic_record(Node& whole, const PieceBase& base, const double* cuts, int m, int step,
                                     double amin, const Intervals& intervals) noexcept {
  const long k0 = tail_ - 1;
  const long block = whole.block;
  const CubicTable& ct = cubic_table(block);
  const BlendBounds& tab = ct.bounds;
  const Segment& g = whole.segment;
  const double L = g.full_length;
  const std::size_t bs = block_slot(block);
  CubicRecord& r = cubic_records_[bs];
  Segment& store = cubics_[bs];
  store = g;
  store.trim_start = store.trim_end = 0.0;  // (next() samples a piece at its offset on the whole cubic)
  r.np = m;
  r.cursor = 0;
  // step 1: the pieces after the first lie on consecutive table intervals (but for flat stretches of the
  // table); all of them on the intervals from r0 on come from the kernel, the others (a trimmed first or
  // last piece over more than one interval) are overwritten below
  int r0 = -1;
  if (step == 1 && m >= 2) {
    int i0, i1;
    intervals(1, i0, i1);
    if (i0 >= 1 && i0 - 1 + m <= 16) {
      r0 = i0 - 1;
      cubic_record_kernels_->record_singles(tab, ct.curvature, g.table.data(), r0, r);
    }
  }
  for (int k = 0; k < m; ++k) {
    int i0, i1;
    intervals(k, i0, i1);
    if (!(r0 >= 0 && i0 == r0 + k && i1 == i0 + 1)) {
      Vec3 U, K, Ua[2], Ka[2];
      tab.bounds(i0, i1, U, K);
      tab.ramps(i0, i1, U, K, Ua, Ka);
      for (int i = 0; i < 3; ++i) {
        r.u_abs[i][k] = U[i];
        r.k_abs[i][k] = K[i];
        for (int d = 0; d < 2; ++d) {
          r.ramp_u[d][i][k] = Ua[d][i];
          r.ramp_k[d][i][k] = Ka[d][i];
        }
      }
      piece_curvature(ct.curvature, g.table, i0, i1, r.curvature[k], r.curvature_rate[k]);
    }
    r.trim_start[k] = cuts[k];
    r.trim_end[k] = L - cuts[k + 1];
    r.len[k] = L - r.trim_start[k] - r.trim_end[k];  // (Segment::length(); ≥ 0: rounding is monotone)
  }
  // the reach coefficients of one piece alone (set_box_reach)
  const auto scalar_reach = [&](int k) {
    PassRecord x;
    x.length = std::max(0.0, r.len[k]);
    Vec3 Ua[2], Ka[2];
    r.ramps(k, Ua, Ka);
    set_box_reach(x, Ua, Ka);
    for (int i = 0; i < 3; ++i) {
      r.alpha[i][k] = x.alpha[i];
      r.beta[i][k] = x.beta[i];
      r.alpha_down[i][k] = x.alpha_down[i];
      r.beta_down[i][k] = x.beta_down[i];
    }
  };
  // the caps and reach coefficients of all pieces at once (the cubic-record kernel)
  unsigned bad = cubic_record_kernels_->caps_reach(r, base.feed_cap, limits_.velocity.data(), limits_.acceleration.data());
  for (int k = 0; bad != 0; ++k, bad >>= 1)
    if (bad & 1u) scalar_reach(k);
  // junction limits: the block's corner at the first piece, the cap before at the others (finish_piece)
  whole.v_junction = std::min(base.v_corner, r.v_max[0]);
  cubic_record_kernels_->junctions(r, base.v_corner);
  r.w_after = -1.0;
  // the node: the whole cubic with its trims (push() and the blend rule read its curve at the end),
  // the first piece's junction and the last piece's cap (the junction after it reads v_max)
  whole.geometry = Geometry::cubic_record;
  whole.bound = SpeedBound::axis_box;
  whole.path_accel = amin;
  whole.path_jerk = inf;
  whole.v_max = r.v_max[m - 1];
  PassRecord& x = pass(k0);
  x.w_junction = r.w_junction[0];
  x.w_backward = 0.0;
  x.length = g.length();
  x.path_accel = amin;
  x.path_jerk = inf;
  x.bound = SpeedBound::axis_box;
  x.line_blend = -1;
  x.cubic = static_cast<int>(bs);
}

// Two curves that meet with equal curvature vectors up to rounding (the pieces of one C² spline, whose
// joint curvatures agree to ~1e-9 relative) must not be capped as a curvature step: a step v²·|Δκ| in
// the acceleration with |Δκ| ≤ 1e-6·max(|κ|, 1e-3) is at most 1e-6 of the centripetal acceleration
// v²·|κ| (≤ A) on a curved joint, and on a nearly straight one (|κ| < 1e-3 /mm) at most
// 1e-9·v² ≤ 1e-3 mm/s² for v ≤ 1 m/s; its third difference over ts2 is then far below any jerk limit.
bool PlannerState::curvature_continuous(const Vec3& k1, const Vec3& k2) noexcept {
  const double scale = std::max({k1.norm(), k2.norm(), 1e-3});
  return (k2 - k1).norm() <= 1e-6 * scale;
}

}  // namespace netshape::motion::detail
