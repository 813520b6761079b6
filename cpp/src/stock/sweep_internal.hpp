#pragma once
// Private pieces shared by the Z-map sweep's translation units: sweep.cpp (the public API),
// line_sweep.cpp (lines: reach, row spans, the kernels' callers) and arc_sweep.cpp (XY arcs).
#include <algorithm>
#include <cmath>

#include "netshape/stock/sweep.hpp"
#include "netshape/stock/zmap.hpp"
#include "stock/kernels/sweep_kernels.hpp"

namespace netshape::stock {

/// Quick reject: a move is skipped when the band bounds of its rows are at least this far below the
/// lowest point its tip reaches [mm] (covers the rounding of the per-node z, ~1e-14 relative).
constexpr double kRejectMargin = 1e-9;
/// A band whose bound is above a move is recomputed exactly once the sweeps since its last exact
/// bound have booked at least this many times its node count (amortised: at most one read of a
/// height per 4 nodes of sweep work).
constexpr double kRefreshWork = 4.0;

/// The sweeps' access to a Z-map (a friend of ZMap): the heights without marking the bounds stale,
/// and the quick reject.
struct SweepAccess {
  static MatrixXdR& heights(ZMap& z) noexcept { return z.heights_; }

  /// True if every height of rows i0 … i1 is at least kRejectMargin below zlow [mm]: a move whose
  /// cutter never reaches below zlow lowers nothing there. Bands whose bound is above are
  /// recomputed when their booked work allows (above); when false, `width` nodes per row are booked
  /// on every band of the rows (the move is swept there).
  static bool above(ZMap& z, int i0, int i1, double zlow, double width) {
    if (z.bounds_stale_) z.init_bounds();
    const double lim = zlow - kRejectMargin;
    const int br = z.band_rows_, b0 = i0 / br, b1 = i1 / br;
    const double band_nodes = static_cast<double>(br) * z.nx_;
    bool ok = true;
    for (int b = b0; b <= b1; ++b) {
      const auto k = static_cast<std::size_t>(b);
      if (z.band_max_[k] <= lim) continue;
      if (static_cast<double>(z.band_work_[k]) >= kRefreshWork * band_nodes) {
        z.refresh_band(b);
        if (z.band_max_[k] <= lim) continue;
      }
      ok = false;
      break;
    }
    if (ok) return true;
    const auto w = static_cast<std::int64_t>(width * br) + 1;
    for (int b = b0; b <= b1; ++b) z.band_work_[static_cast<std::size_t>(b)] += w;
    return false;
  }
};

namespace detail {

using kernels::inf;
using kernels::LineSetup;
constexpr double two_pi = 2.0 * pi;
/// Horizontal move length below which a line is treated as vertical (plunge) [mm].
constexpr double vertical_eps = 1e-9;
/// Tolerance of the 1-D minimisations along arcs [rad].
constexpr double angle_tol = 1e-10;

enum ProfileKind { kFlat = 0, kBall = 1, kBull = 2 };

inline ProfileKind kind_of(const cutter::Cutter& c) {
  switch (c.kind) {
    case cutter::CutterKind::ball: return kBall;
    case cutter::CutterKind::bull: return kBull;
    case cutter::CutterKind::flat:
    default: return kFlat;
  }
}

/// lift with d clamped to R (rounding at the edge of the footprint must not give +inf)
inline double lift_c(const TipProfile& p, double d) noexcept { return p.lift(std::min(d, p.radius)); }

/// index range of nodes with centre in [lo, hi] along an axis with origin o, cell size h, n nodes
inline bool node_range(double lo, double hi, double o, double h, int n, int& k0, int& k1) noexcept {
  double a = std::ceil((lo - o) / h - 0.5 - 1e-9);
  double b = std::floor((hi - o) / h - 0.5 + 1e-9);
  a = std::max(a, 0.0);
  b = std::min(b, static_cast<double>(n - 1));
  if (!(a <= b)) return false;
  k0 = static_cast<int>(a);
  k1 = static_cast<int>(b);
  return true;
}

/// h = max(z, bottom) where that is lower than h, booking the removed height and the lowered node.
inline void lower(double& h, double z, double bottom, SweepStats& st) noexcept {
  if (z < h) {
    const double nz = z > bottom ? z : bottom;
    if (nz < h) {
      st.removed_volume += h - nz;  // scaled by the cell area at the end
      ++st.nodes_lowered;
      h = nz;
    }
  }
}

/// The move a → b of the tool tip.
LineSetup make_line(const Vec3& a, const Vec3& b);
/// Lowest z the tip of profile p reaches over node (x, y) along the line s (+inf: never over it).
double lowest_reach(const TipProfile& p, const LineSetup& s, double x, double y) noexcept;
/// Sweep the line a → b through the Z-map; removed_volume in mm³.
SweepStats sweep_line_impl(ZMap& zm, const TipProfile& p, ProfileKind kind, const Vec3& a, const Vec3& b);

/// An arc in the XY plane with a constant radius (planar or helical).
struct ArcSetup {
  double cx = 0, cy = 0;  // centre [mm]
  double r = 0;           // axis radius [mm]
  double th0 = 0;         // start angle [rad]
  double sgn = 1;         // +1 counter-clockwise, −1 clockwise
  double total = 0;       // |sweep| [rad]
  double z0 = 0;          // start z [mm]
  double kz = 0;          // dz per rad of travel [mm/rad]
};

/// Sweep the arc s through the Z-map; adds to st (removed_volume in mm² × heights, scaled by the caller).
void sweep_arc(ZMap& zm, const TipProfile& p, ProfileKind kind, const ArcSetup& s, SweepStats& st);

}  // namespace detail
}  // namespace netshape::stock
