#pragma once
/// \file sweep.hpp
/// Material removal: sweep a 3-axis cutter (tool axis +Z) along lines and arcs over a Z-map.
///
/// Exactness. For every node q the sweep computes the lowest z the cutter's lower surface reaches
/// over the whole move, not only at sample points, and sets height(q) = max(bottom, min(height(q),
/// that z)). With the tip on the move P(t) and g the tip profile (tip_profile.hpp):
///
///   line A→B:  with σ the horizontal distance travelled, s the node's distance from the line and
///              τ_q its foot point, z(σ) = A_z + m·σ + g(sqrt(s² + (σ − τ_q)²)), m = Δz/Δxy.
///              This is convex in σ (g convex non-decreasing, the distance convex), so the minimum
///              over the feasible σ (where the node is under the cutter) is unique:
///              flat  → an end of the feasible interval (z linear in σ), closed form;
///              ball  → σ* = τ_q − m·ρ/sqrt(1 + m²), ρ = sqrt(R² − s²), clamped; closed form;
///              bull  → closed form for horizontal moves; ramps: root of the (monotone)
///                      derivative by Newton steps kept inside a bisection bracket (steps
///                      below 1e-9 mm end it).
///              horizontal moves (all cutters) use the nearest point of the segment directly:
///              d² = s² + (τ_q − clamp(τ_q, 0, L))² (one square root, none for flat).
///              Vertical moves (plunges, |Δxy| ≤ 1e-9 mm): min(A_z, B_z) + g(d).
///   XY arc (G17, incl. helical), constant radius: the node is under the cutter while the axis angle
///              is within ±α of the node's angle (α from the triangle centre–axis–node), once per turn.
///              planar, any profile → the feasible angle nearest the node's angle, closed form;
///              helical flat → the first/last feasible angle (z linear in angle), closed form;
///              helical ball/bull → per feasible window, 24-point bracketing then golden-section
///              refinement to 1e-10 rad (exact when the lift is unimodal within one bracket,
///              which holds for tool-path arcs; see docs/stock.md).
///   other arcs (G18/G19 planes, or radius changing between start and end by more than 1e-9 mm):
///              split into chords with at most `SweepOptions::chord_tolerance` deviation, each
///              chord swept exactly as a line.
///
/// Quick reject: a move whose tip never goes below the height bound of the rows it covers
/// (ZMap::height_bound, per band of rows, kept as an upper bound and recomputed lazily) returns at
/// once with nothing visited: retracts and rapids above the stock cost a few reads per row band.
///
/// Cost: only the nodes whose centres can be under the cutter are visited (per row, the X range of
/// the stadium the line sweeps; for arcs the bounding box of the arc grown by R). No allocation per
/// move (flat/ball ramps use a per-thread buffer of per-column terms that grows to the widest move).

#include <cstdint>

#include "netshape/core/types.hpp"
#include "netshape/cutter/cutter.hpp"
#include "netshape/stock/tip_profile.hpp"
#include "netshape/stock/zmap.hpp"
#include "netshape/toolpath/block.hpp"
#include "netshape/toolpath/toolpath.hpp"

namespace netshape::stock {

/// Options of the program-level sweeps.
struct SweepOptions {
  double chord_tolerance = 1e-3;  ///< chord error for arcs that are split into lines [mm]
  bool include_rapids = true;     ///< sweep G0 moves too (a rapid through material is reported)
  bool merge_collinear = true;    ///< sweep runs of collinear lines as one line (same result, faster)
  void validate() const;
};

/// What a sweep did.
struct SweepStats {
  std::int64_t moves = 0;          ///< line/arc sweeps performed (after merging/chording)
  std::int64_t nodes_visited = 0;  ///< nodes whose lowest reach was evaluated
  std::int64_t nodes_lowered = 0;  ///< nodes whose height went down
  double removed_volume = 0.0;     ///< material removed, pillar model [mm³]
  std::int64_t rapids_cutting = 0; ///< rapid (G0) blocks that removed material
  SweepStats& operator+=(const SweepStats& o) noexcept;
};

/// Lowest z [mm] the cutter's tip surface reaches above (x, y) while its tip moves from a to b
/// (straight line); +inf if the cutter never covers (x, y). The per-node kernel of sweep_line.
double lowest_reach_line(const TipProfile& profile, const Vec3& a, const Vec3& b, double x, double y) noexcept;

/// Sweep the cutter tip along the straight line a → b [mm].
SweepStats sweep_line(ZMap& zmap, const cutter::Cutter& cutter, const Vec3& a, const Vec3& b);

/// Sweep the cutter tip along n straight lines starts(k) → ends(k) [mm], in order: the same heights
/// bit for bit as n calls of sweep_line, with the summed stats (moves = n), without a per-move call
/// from Python. starts and ends are (n, 3) (n ≥ 0; n = 0 does nothing); all input is checked
/// (shapes, finite) before any height changes.
SweepStats sweep_lines(ZMap& zmap, const cutter::Cutter& cutter, const Eigen::Ref<const MatrixXdR>& starts,
                       const Eigen::Ref<const MatrixXdR>& ends);

/// Sweep along the polyline through the (n, 3) points [mm] (n ≥ 1; one point = a stationary cut).
/// The fast path for many short blocks: one call, no per-block overhead; with `merge_collinear`
/// runs of collinear segments going the same way are swept as one line (identical result).
SweepStats sweep_polyline(ZMap& zmap, const cutter::Cutter& cutter, const Eigen::Ref<const Points3>& points,
                          bool merge_collinear = true);

/// Sweep along one block (line, rapid or arc in any plane) [mm].
SweepStats sweep_block(ZMap& zmap, const cutter::Cutter& cutter, const toolpath::Block& block,
                       const SweepOptions& options = {});

/// Sweep a whole program in order.
SweepStats sweep(ZMap& zmap, const cutter::Cutter& cutter, const toolpath::Toolpath& program,
                 const SweepOptions& options = {});

}  // namespace netshape::stock
