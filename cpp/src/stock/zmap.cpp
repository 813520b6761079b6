#include "netshape/stock/zmap.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "netshape/core/error.hpp"

namespace netshape::stock {

namespace {
void check_footprint(double x0, double x1, double y0, double y1) {
  NETSHAPE_CHECK_FINITE("zmap.x0", x0);
  NETSHAPE_CHECK_FINITE("zmap.x1", x1);
  NETSHAPE_CHECK_FINITE("zmap.y0", y0);
  NETSHAPE_CHECK_FINITE("zmap.y1", y1);
  NETSHAPE_CHECK(x1 > x0, "zmap.x1", x1, "must be greater than x0 [mm]");
  NETSHAPE_CHECK(y1 > y0, "zmap.y1", y1, "must be greater than y0 [mm]");
}

void check_count(double n_x, double n_y) {
  const double n = n_x * n_y;
  NETSHAPE_CHECK(n <= static_cast<double>(ZMap::max_nodes), "zmap.nodes", n,
                 "too many grid nodes (at most 1e8): use a coarser spacing or a smaller footprint");
}
}  // namespace

ZMap::ZMap(double x0, double x1, double y0, double y1, double spacing, double top, double bottom) {
  check_footprint(x0, x1, y0, y1);
  NETSHAPE_CHECK_FINITE("zmap.spacing", spacing);
  NETSHAPE_CHECK(spacing > 0.0, "zmap.spacing", spacing, "must be positive [mm]");
  NETSHAPE_CHECK_FINITE("zmap.top", top);
  NETSHAPE_CHECK_FINITE("zmap.bottom", bottom);
  NETSHAPE_CHECK(bottom < top, "zmap.bottom", bottom, "must be below the top [mm]");
  // 1e-9 relative slack so that 100 / 0.1 gives 1000 cells, not 1001.
  const double fx = std::ceil((x1 - x0) / spacing * (1.0 - 1e-12) - 1e-9);
  const double fy = std::ceil((y1 - y0) / spacing * (1.0 - 1e-12) - 1e-9);
  NETSHAPE_CHECK(fx < 2e9 && fy < 2e9, "zmap.spacing", spacing, "too small for the footprint [mm]");
  check_count(std::max(fx, 1.0), std::max(fy, 1.0));
  x0_ = x0;
  x1_ = x1;
  y0_ = y0;
  y1_ = y1;
  nx_ = std::max(1, static_cast<int>(fx));
  ny_ = std::max(1, static_cast<int>(fy));
  dx_ = (x1 - x0) / nx_;
  dy_ = (y1 - y0) / ny_;
  bottom_ = bottom;
  heights_.setConstant(ny_, nx_, top);
  size_bands(top);  // every height is top: the bounds are exact without a pass over the heights
}

ZMap ZMap::from_heights(const MatrixXdR& heights, double x0, double x1, double y0, double y1, double bottom) {
  check_footprint(x0, x1, y0, y1);
  NETSHAPE_CHECK_FINITE("zmap.bottom", bottom);
  NETSHAPE_CHECK(heights.rows() >= 1 && heights.cols() >= 1, "zmap.heights.shape", heights.rows(),
                 "must have at least one row and one column");
  check_count(static_cast<double>(heights.rows()), static_cast<double>(heights.cols()));
  ZMap z;
  z.x0_ = x0;
  z.x1_ = x1;
  z.y0_ = y0;
  z.y1_ = y1;
  z.ny_ = static_cast<int>(heights.rows());
  z.nx_ = static_cast<int>(heights.cols());
  z.dx_ = (x1 - x0) / z.nx_;
  z.dy_ = (y1 - y0) / z.ny_;
  z.bottom_ = bottom;
  z.set_heights(heights);
  return z;
}

void ZMap::set_heights(const MatrixXdR& heights) {
  NETSHAPE_CHECK(heights.rows() == ny_ && heights.cols() == nx_, "zmap.heights.shape",
                 std::to_string(heights.rows()) + "x" + std::to_string(heights.cols()),
                 "must equal (ny, nx) of the grid");
  for (Eigen::Index i = 0; i < heights.size(); ++i) {
    const double h = heights.data()[i];
    NETSHAPE_CHECK_FINITE("zmap.heights", h);
    NETSHAPE_CHECK(h >= bottom_, "zmap.heights", h, "must not be below the bottom [mm]");
  }
  heights_ = heights;
  init_bounds();
}

void ZMap::size_bands(double bound) {
  band_rows_ = nx_ >= 64 ? 1 : (64 + nx_ - 1) / nx_;
  const auto nb = static_cast<std::size_t>((ny_ + band_rows_ - 1) / band_rows_);
  band_max_.assign(nb, bound);
  band_work_.assign(nb, 0);
  bounds_stale_ = false;
}

void ZMap::init_bounds() {
  size_bands(0.0);
  for (int b = 0; b < static_cast<int>(band_max_.size()); ++b) refresh_band(b);
}

void ZMap::refresh_band(int b) {
  const int r0 = b * band_rows_, r1 = std::min(ny_, r0 + band_rows_);
  // the band's rows are contiguous: one linear (vectorised) max
  band_max_[static_cast<std::size_t>(b)] =
      Eigen::Map<const Eigen::VectorXd>(heights_.data() + static_cast<std::size_t>(r0) * nx_,
                                        static_cast<Eigen::Index>(r1 - r0) * nx_)
          .maxCoeff();
  band_work_[static_cast<std::size_t>(b)] = 0;
}

double ZMap::height_bound(int i0, int i1) const noexcept {
  if (bounds_stale_) return std::numeric_limits<double>::infinity();
  i0 = std::max(i0, 0);
  i1 = std::min(i1, ny_ - 1);
  double m = -std::numeric_limits<double>::infinity();
  for (int b = i0 / band_rows_; b <= i1 / band_rows_ && i0 <= i1; ++b) m = std::max(m, band_max_[static_cast<std::size_t>(b)]);
  return m;
}

double ZMap::volume() const noexcept { return (heights_.array() - bottom_).sum() * dx_ * dy_; }

bool ZMap::cell_of(double x, double y, int& i, int& j) const noexcept {
  if (!(x >= x0_ && x <= x1_ && y >= y0_ && y <= y1_)) return false;  // also rejects NaN
  j = std::min(nx_ - 1, static_cast<int>((x - x0_) / dx_));
  i = std::min(ny_ - 1, static_cast<int>((y - y0_) / dy_));
  return true;
}

double ZMap::cell_height(double x, double y) const noexcept {
  int i, j;
  if (!cell_of(x, y, i, j)) return std::numeric_limits<double>::quiet_NaN();
  return heights_(i, j);
}

double ZMap::height_at(double x, double y) const noexcept {
  if (!(x >= x0_ && x <= x1_ && y >= y0_ && y <= y1_)) return std::numeric_limits<double>::quiet_NaN();
  // continuous node coordinates, clamped to the outermost nodes
  const double u = std::clamp((x - x0_) / dx_ - 0.5, 0.0, static_cast<double>(nx_ - 1));
  const double v = std::clamp((y - y0_) / dy_ - 0.5, 0.0, static_cast<double>(ny_ - 1));
  const int j = std::min(static_cast<int>(u), std::max(nx_ - 2, 0));
  const int i = std::min(static_cast<int>(v), std::max(ny_ - 2, 0));
  const double fu = nx_ > 1 ? u - j : 0.0;
  const double fv = ny_ > 1 ? v - i : 0.0;
  const int j1 = std::min(j + 1, nx_ - 1);
  const int i1 = std::min(i + 1, ny_ - 1);
  const double h0 = heights_(i, j) * (1 - fu) + heights_(i, j1) * fu;
  const double h1 = heights_(i1, j) * (1 - fu) + heights_(i1, j1) * fu;
  return h0 * (1 - fv) + h1 * fv;
}

bool ZMap::is_material(const Vec3& p) const noexcept {
  int i, j;
  if (!cell_of(p.x(), p.y(), i, j)) return false;
  return p.z() >= bottom_ && p.z() < heights_(i, j);
}

VectorXd ZMap::height_at_points(const Eigen::Ref<const MatrixXdR>& xy) const {
  NETSHAPE_CHECK(xy.cols() == 2 || xy.cols() == 3, "points.shape[1]", xy.cols(), "must be 2 or 3");
  VectorXd out(xy.rows());
  for (Eigen::Index k = 0; k < xy.rows(); ++k) out[k] = height_at(xy(k, 0), xy(k, 1));
  return out;
}

VectorXd ZMap::cell_height_points(const Eigen::Ref<const MatrixXdR>& xy) const {
  NETSHAPE_CHECK(xy.cols() == 2 || xy.cols() == 3, "points.shape[1]", xy.cols(), "must be 2 or 3");
  VectorXd out(xy.rows());
  for (Eigen::Index k = 0; k < xy.rows(); ++k) out[k] = cell_height(xy(k, 0), xy(k, 1));
  return out;
}

VectorXb ZMap::is_material_points(const Eigen::Ref<const Points3>& p) const {
  VectorXb out(p.rows());
  for (Eigen::Index k = 0; k < p.rows(); ++k) out[k] = is_material(Vec3(p(k, 0), p(k, 1), p(k, 2)));
  return out;
}

}  // namespace netshape::stock
