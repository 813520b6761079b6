// The line-blend kernels for plain x86-64 (and any other CPU), their tables and the choice of the
// instruction set (line_blend.hpp).
#include "line_blend.hpp"

#include "core/dispatch.hpp"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <limits>

#define NETSHAPE_LINE_BLEND_ISA plain
#include "line_blend_kernels.inc"
#undef NETSHAPE_LINE_BLEND_ISA

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

namespace {
const LineBlendKernels plain_kernels{&plain::build, &plain::freeze, "plain"};
}  // namespace

const LineBlendKernels& line_blend_kernels_plain() { return plain_kernels; }

#if defined(NETSHAPE_MOTION_AVX2)
extern const LineBlendKernels avx2_line_blend_kernels;  // line_blend_avx2.cpp
#endif

const LineBlendKernels& line_blend_kernels() {
  static const LineBlendKernels* const chosen = [] {
    const LineBlendKernels* best = &plain_kernels;
#if defined(NETSHAPE_MOTION_AVX2)
    if (simd::active_isa() >= simd::Isa::avx2) best = &avx2_line_blend_kernels;
#endif
    return best;
  }();
  return *chosen;
}

}  // namespace netshape::motion::detail
