// Cubic blocks (cubic.hpp) in the planner: their validation, the whole-block node (the Bézier with its
// arc-length table, bounds over all of it), the cut into pieces at table nodes once the block's end is
// known (per-axis bounds per piece, as the corner blends' pieces), and the test for a curvature-
// continuous joint. push() (planner_push.cpp) sets their junctions like any block's.
#include <algorithm>
#include <array>
#include <cmath>

#include "blend_bounds.hpp"
#include "planner_geometry.hpp"
#include "planner_state.hpp"

namespace netshape::motion::detail {

namespace {
// index of the table interval holding arc length s (from the untrimmed start), 0..15
int interval_at(const std::array<double, 17>& table, double s) {
  const auto it = std::upper_bound(table.begin(), table.end(), s);
  return std::clamp(static_cast<int>(it - table.begin()) - 1, 0, 15);
}
}  // namespace

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
  std::array<Vec3, 17> T, Kv;
  n.segment = Segment::blend(b.start, c.c1, c.c2, b.end, source, &T, &Kv);
  n.segment.block = b;  // the chord (kind line) with the block's feed and line number
  CubicTable& ct = cubic_table(source);
  ct.bounds.fill(T, Kv);
  for (std::size_t i = 0; i < 17; ++i) ct.curvature[i] = Kv[i].norm();
  ct.bounds.bounds(0, 16, n.tangent_bound, n.curvature_bound);
  ct.bounds.ramps(0, 16, n.tangent_bound, n.curvature_bound, n.ramp_tangent, n.ramp_curvature);
  n.geometry = Geometry::in_node;
}

// The trimmed window [a, b] of the cubic (blends at either end trim it) is cut at the table nodes
// every 16/cubic_piece_count() intervals that lie inside it (without jerk limits fewer for gentle
// cubics, below); a piece's bounds are those of the table
// intervals it touches (valid on any part of them, so on the trimmed end pieces too). In jerk mode
// each piece gets the largest curvature and |dκ/ds| at its table nodes, as the corner blends' pieces.
// The whole-block node becomes the first piece; the others are written in place in the ring slots
// after it (free: push() keeps nodes_per_push of them), with every Node field the planner reads
// before the freeze set. The last piece holds the whole block's segment (push() and the blend rule
// read the curve at its end); the ones between keep only kind, trims, length, curvature and source
// (Geometry::in_cubic_store), the rest of the segment stays once in the cubic store.
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
    // the tangent bounds allow) is one piece, a moderate one (at most 25 %) four: finer pieces would
    // only relax a bound that hardly binds, and each piece costs a node and its passes
    const Vec3& U = whole.tangent_bound;  // the whole cubic's bounds (init_cubic_node)
    const Vec3& K = whole.curvature_bound;
    double vcap = base.feed_cap;
    for (int i = 0; i < 3; ++i)
      if (U[i] > 0) vcap = std::min(vcap, limits_.velocity[i] / U[i]);
    double share = 0;
    for (int i = 0; i < 3; ++i) share = std::max(share, K[i] * vcap * vcap / limits_.acceleration[i]);
    if (share <= 0.02) step = 16;
    else if (share <= 0.25) step = 4;
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
  const AxisMinima minima = axis_minima(g);  // the same axes move on every piece
  if (step == 1) tab.singles();  // the pieces are single table intervals (but at trimmed ends)
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
    const double s0 = cuts[k], s1 = cuts[k + 1];
    x.segment.trim_start = s0;
    x.segment.trim_end = L - s1;
    // the intervals [i0, i1) that hold [s0, s1]: i0 is the interval holding s0 (interval_at), i1 the
    // first table node at or past s1. A cut on table node i, where the table (non-decreasing) rises
    // on both sides of it, gives them without a search: interval_at(table[i]) = i when
    // table[i + 1] > table[i], and the first node at or past table[i] is i when table[i − 1] < table[i]
    const int n0 = node_at[k], n1 = node_at[k + 1];
    const auto tab_at = [&g](int i) { return g.table[static_cast<std::size_t>(i)]; };
    const int i0 = n0 > 0 && tab_at(n0 + 1) > tab_at(n0) ? n0 : interval_at(g.table, s0);
    const int first_at = n1 > 0 && tab_at(n1 - 1) < tab_at(n1)
                             ? n1
                             : static_cast<int>(std::lower_bound(g.table.begin(), g.table.end(), s1) - g.table.begin());
    const int i1 = std::clamp(first_at, i0 + 1, 16);
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
