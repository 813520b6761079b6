// The line-blend kernels' constant tables and the choice of their instruction set (kernels/line_blend_kernels.hpp;
// the kernels themselves are in kernels/line_blend.cpp).
#include "motion/kernels/line_blend_kernels.hpp"

#include <algorithm>

#include "core/dispatch.hpp"


namespace netshape::motion::detail {

LineBlendTables::LineBlendTables() {
  const double gx = 0.7745966692414834, h = 0.5 / 16.0;
  for (int i = 0; i < 8; ++i) {
    const double m = (i + 0.5) / 16.0, us[3] = {m, m - h * gx, m + h * gx};
    for (int j = 0; j < 3; ++j) {
      const double u = us[j], aa = (1 - u) * (1 - u), bb = u * u;
      gp[8 * j + i] = aa * aa + bb * bb;
      gq[8 * j + i] = 2.0 * aa * bb;
    }
  }
  for (int i = 0; i < 12; ++i) {
    const double u = std::min(i, 8) / 16.0, aa = (1 - u) * (1 - u), bb = u * u;
    np[i] = aa * aa + bb * bb;
    nq[i] = 2.0 * aa * bb;
    w[i] = u * (1 - u);
  }
  for (int m = 0; m < n_cut_lanes; ++m) {
    const double u = cuts_lines[std::min(m, n_cuts_lines)] / 16.0, aa = (1 - u) * (1 - u), bb = u * u;
    cp[m] = aa * aa + bb * bb;
    cq[m] = 2.0 * aa * bb;
    ca[m] = aa;
    cb[m] = bb;
    cw[m] = u * (1 - u);
  }
}

const LineBlendTables& line_blend_tables() {
  static const LineBlendTables tables;
  return tables;
}

const LineBlendKernels& line_blend_kernels_plain() { return baseline::line_blend_kernel_table; }

const LineBlendKernels& line_blend_kernels() {
  static const LineBlendKernels& chosen = NETSHAPE_SIMD_SELECT(detail, line_blend_kernel_table);
  return chosen;
}

}  // namespace netshape::motion::detail
