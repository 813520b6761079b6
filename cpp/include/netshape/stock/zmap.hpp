#pragma once
/// \file zmap.hpp
/// The Z-map workpiece (Kim et al. §2): a regular grid of vertical pillars over a rectangle in the
/// machine XY plane, each storing the height of the material top at its node [mm].
///
/// Grid: the footprint [x0, x1] × [y0, y1] is cut into nx × ny cells of size dx × dy; each cell has
/// one node at its centre:
///
///     node (i, j)  at  x = x0 + (j + ½)·dx,  y = y0 + (i + ½)·dy,   i = 0 … ny−1 (row), j = 0 … nx−1
///
/// nx = ceil((x1 − x0)/h), dx = (x1 − x0)/nx (so dx ≤ h and the footprint is kept exactly; the same
/// for y). Heights are an (ny, nx) row-major array: heights(i, j) is the top of pillar (i, j).
/// `bottom` is the underside of the stock: heights never go below it (a cut through the stock leaves
/// height = bottom, i.e. no material in that pillar).
///
/// Two readings of the heights, both documented per query:
/// - pillar (cell) model: a point (x, y) belongs to the cell that contains it and the material there
///   spans [bottom, heights(i, j)). `cell_height` and `is_material` use it (the Kim et al. reading).
/// - smooth surface: `height_at` interpolates bilinearly between the four surrounding nodes (clamped
///   to the outermost nodes within the footprint); use it to measure or plot the surface.

#include <cstdint>
#include <vector>

#include "netshape/core/types.hpp"

namespace netshape::stock {

/// (n,) boolean vector (NumPy bool).
using VectorXb = Eigen::Matrix<bool, Eigen::Dynamic, 1>;

class ZMap {
 public:
  /// Largest number of nodes a Z-map may have (10⁸ nodes = 800 MB of heights); asking for more
  /// throws std::invalid_argument before allocating.
  static constexpr std::int64_t max_nodes = 100'000'000;

  /// A flat block: footprint [x0, x1] × [y0, y1] [mm], node spacing at most `spacing` [mm], top at
  /// z = `top` [mm], underside at z = `bottom` [mm] (bottom < top).
  ZMap(double x0, double x1, double y0, double y1, double spacing, double top, double bottom);

  /// A Z-map from an (ny, nx) array of node heights [mm] over the footprint [x0, x1] × [y0, y1]
  /// (dx = (x1 − x0)/nx, dy = (y1 − y0)/ny). Heights below `bottom` are an error.
  static ZMap from_heights(const MatrixXdR& heights, double x0, double x1, double y0, double y1, double bottom);

  // --- grid ------------------------------------------------------------------------------------
  int nx() const noexcept { return nx_; }     ///< number of node columns (along X)
  int ny() const noexcept { return ny_; }     ///< number of node rows (along Y)
  double x0() const noexcept { return x0_; }  ///< footprint [mm]
  double x1() const noexcept { return x1_; }
  double y0() const noexcept { return y0_; }
  double y1() const noexcept { return y1_; }
  double dx() const noexcept { return dx_; }  ///< cell size along X [mm]
  double dy() const noexcept { return dy_; }  ///< cell size along Y [mm]
  double bottom() const noexcept { return bottom_; }  ///< underside of the stock [mm]
  double node_x(int j) const noexcept { return x0_ + (j + 0.5) * dx_; }  ///< X of node column j [mm]
  double node_y(int i) const noexcept { return y0_ + (i + 0.5) * dy_; }  ///< Y of node row i [mm]
  /// Cell (i, j) containing (x, y); false if (x, y) is outside the footprint. Points on the
  /// x1 / y1 edge belong to the last cell.
  bool cell_of(double x, double y, int& i, int& j) const noexcept;

  // --- heights ---------------------------------------------------------------------------------
  /// (ny, nx) node heights [mm], row-major.
  const MatrixXdR& heights() const noexcept { return heights_; }
  /// Mutable heights. Keep them finite and ≥ bottom. Handing them out marks the height bounds of
  /// the quick reject (below) stale; the next sweep recomputes them.
  MatrixXdR& heights_mut() noexcept {
    bounds_stale_ = true;
    return heights_;
  }
  /// Replace all heights (same shape, finite, ≥ bottom) [mm].
  void set_heights(const MatrixXdR& heights);
  /// Material volume above the bottom, pillar model [mm³].
  double volume() const noexcept;
  double min_height() const noexcept { return heights_.minCoeff(); }  ///< [mm]
  double max_height() const noexcept { return heights_.maxCoeff(); }  ///< [mm]

  // --- queries ---------------------------------------------------------------------------------
  /// Pillar height of the cell containing (x, y) [mm]; NaN outside the footprint.
  double cell_height(double x, double y) const noexcept;
  /// Bilinear interpolation of the node heights at (x, y) [mm] (between the outermost nodes and the
  /// footprint edge the nearest row/column is used); NaN outside the footprint.
  double height_at(double x, double y) const noexcept;
  /// True if p lies in material: inside the footprint and bottom ≤ p.z < cell height (pillar model).
  bool is_material(const Vec3& p) const noexcept;

  /// Bulk `height_at` over (n, 2) or (n, 3) points (columns 0 and 1 are x, y) → (n,) [mm].
  VectorXd height_at_points(const Eigen::Ref<const MatrixXdR>& xy) const;
  /// Bulk `cell_height` → (n,) [mm].
  VectorXd cell_height_points(const Eigen::Ref<const MatrixXdR>& xy) const;
  /// Bulk `is_material` over (n, 3) points → (n,) bool.
  VectorXb is_material_points(const Eigen::Ref<const Points3>& p) const;

  // --- height bounds (quick reject of moves above the stock) -------------------------------------
  /// Rows per band of the height bounds (≥ 1; one row when nx ≥ 64).
  int band_rows() const noexcept { return band_rows_; }
  /// Upper bound of the heights of rows i0 … i1 [mm] (≥ their true maximum; exact after
  /// construction and set_heights, and for bands refreshed since; sweeps only lower heights, so the
  /// bound stays valid without being updated).
  double height_bound(int i0, int i1) const noexcept;

 private:
  friend struct SweepAccess;  // the sweeps (src/stock/sweep_internal.hpp): heights without staling the bounds, bounds
  ZMap() = default;
  void size_bands(double bound);  // band sizes (≥ 64 nodes per band), every band's bound set to `bound`
  void init_bounds();           // band sizes and exact bounds from the heights
  void refresh_band(int b);     // exact bound of band b
  int band_rows_ = 1;
  std::vector<double> band_max_;          // per band of band_rows_ rows: upper bound of the heights [mm]
  std::vector<std::int64_t> band_work_;   // per band: nodes swept there since its bound was exact
  bool bounds_stale_ = false;             // heights_mut() was handed out: bounds unknown
  double x0_ = 0, x1_ = 0, y0_ = 0, y1_ = 0, dx_ = 1, dy_ = 1, bottom_ = 0;
  int nx_ = 0, ny_ = 0;
  MatrixXdR heights_;
};

}  // namespace netshape::stock
