#pragma once
// The Z-map sweep's SIMD kernels (private): the plain data they take and their two tables.
//
// RampKernels (kernels/ramp.cpp): flat and ball ramps and level lines — most lines of a program — one
// call per move: the node span of every row (row_spans), then per row the nodes taken W at a time at
// column multiples of W (W = 8 with AVX-512, 4 with AVX2, 1 on the baseline), the row kAhead rows on
// prefetched one cache line per chunk. RowKernels (kernels/rows.cpp): one grid row at a time for
// plunges and bull-nose lines, loops that `#pragma omp simd` vectorises. Every node is computed with
// the arithmetic of the NumPy reference in its order, so flat and ball heights are bit-identical to it
// on every instruction set; only the removed-volume sum of the ramp kernels is added in lane order.
#include <cstdint>
#include <limits>

#include "core/dispatch.hpp"
#include "netshape/stock/tip_profile.hpp"

namespace netshape::stock::kernels {

inline constexpr double inf = std::numeric_limits<double>::infinity();
/// Tolerance of the 1-D minimisations along lines [mm].
inline constexpr double line_tol = 1e-10;
/// Newton steps shorter than this end the bull-nose ramp search [mm]; the next step would be far
/// shorter still (quadratic convergence), and F is flat at its minimum.
inline constexpr double newton_tol = 1e-9;
/// A node (chunk, block) is skipped when its height is at least this far below a lower bound of the
/// cutter there [mm] (covers rounding): exact, a skipped node would not have changed.
inline constexpr double kSkipMargin = 1e-9;
/// Slack of the row spans of ramps [index units]: a node this close outside the stadium is visited
/// too (the per-node test rejects it), so rounding in the span can never drop a covered node.
inline constexpr double kSpanSlack = 1e-6;
/// Rows prefetched ahead by the ramp kernels.
inline constexpr int kAhead = 4;
/// Nodes per skip test of the row kernels.
inline constexpr int kBlock = 32;
/// Nodes per batch of the bull-nose ramp's lane-parallel Newton iteration.
inline constexpr int kBullChunk = 256;

/// A line move of the tool tip, horizontal part as unit direction and length.
struct LineSetup {
  double ax = 0, ay = 0, az = 0;  ///< start of the tip path [mm]
  double ex = 1, ey = 0;          ///< unit horizontal direction
  double len = 0;                 ///< horizontal length [mm]
  double m = 0;                   ///< dz per mm of horizontal travel
  double kball = 0;               ///< m / sqrt(1 + m²)
  double zv = 0;                  ///< vertical moves: min(A_z, B_z) [mm]
  bool vertical = false;
};

/// Per-move constants of the row spans: end points, direction and its reciprocals (a direction
/// within 1e-15 of an axis uses the axis-parallel form: use_ex / use_ey false), grid origin and steps.
struct SpanSetup {
  double ax, ay, bx, by, r, r2, ex, ey, len, iex, iey, y0, dy, x0, idx;
  bool use_ex, use_ey;
};

/// One whole flat or ball move for the ramp kernels: the heights H (row-major, nx columns), rows
/// i0 … i1 with their node spans j0s/j1s (index i − i0), and the per-column terms qx·e_x (tqx) and
/// qx·e_y (spx) of columns cmin, cmin + 1, … (padded to whole chunks).
struct MoveArgs {
  double* H;
  int nx;
  double y0, dy;  ///< node row i lies at y0 + (i + ½)·dy [mm]
  LineSetup s;
  double R, bottom;
  int i0, i1;
  const int *j0s, *j1s;
  const double *tqx, *spx;
  int cmin;
};

/// Accumulated effect of one move.
struct MoveOut {
  double vol = 0.0;          ///< removed height summed over nodes [mm] (× cell area later)
  std::int64_t lowered = 0;  ///< nodes whose height went down
  std::int64_t visited = 0;  ///< nodes of the stadium rows
};

/// One row of nodes: node k sits at x = x0 + (jb + k)·dx (jb = j0 + ½), y; h points at node j0.
struct Row {
  double x0 = 0, dx = 1, jb = 0.5;  ///< grid X origin [mm], cell size [mm], j0 + ½
  double qy = 0;                    ///< node y − A_y [mm]
  int n = 0;                        ///< nodes in the row segment
};

/// Accumulated effect of the row kernels.
struct RowOut {
  double vol = 0.0;          ///< removed height summed over nodes [mm] (× cell area later)
  std::int64_t lowered = 0;  ///< nodes whose height went down
};

/// Scratch of the bull-nose ramp's Newton iteration, one batch of nodes (caller-owned).
struct BullLanes {
  double tq[kBullChunk], sp2[kBullChunk], lo[kBullChunk], hi[kBullChunk];
  double a[kBullChunk], b[kBullChunk], x[kBullChunk], sig[kBullChunk];
  int node[kBullChunk];
  unsigned char done[kBullChunk];
};

using MoveFn = void (*)(const MoveArgs&, MoveOut&);
struct RampKernels {
  /// Node spans of rows i0 … i0 + n − 1 (j0s[k] > j1s[k] when row i0 + k has none).
  void (*row_spans)(const SpanSetup& q, int i0, int n, int jlo, int jhi, int* j0s, int* j1s);
  /// [0 flat, 1 ball][0 level (m = 0), 1 up (m > 0), 2 down (m < 0)]
  MoveFn move[2][3];
};

using RowFn = void (*)(const LineSetup& s, const TipProfile& p, double r2, const Row& row, double bottom,
                       double* h, RowOut& out);
struct RowKernels {
  RowFn vertical;    ///< plunge, any cutter
  RowFn bull_level;  ///< bull-nose line with m = 0
  void (*bull_ramp)(const LineSetup& s, const TipProfile& p, double r2, const Row& row, double bottom,
                    double* h, RowOut& out, BullLanes& lanes);
};

NETSHAPE_SIMD_DECLARE(RampKernels, ramp_kernels)
NETSHAPE_SIMD_DECLARE(RowKernels, row_kernels)

}  // namespace netshape::stock::kernels
