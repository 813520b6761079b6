// The line-blend kernels built for AVX2 (without FMA: the same bits as the plain ones). CMake
// compiles this file with -mavx2 on x86-64 only and defines NETSHAPE_MOTION_AVX2; its code runs only
// after line_blend_kernels() has checked the CPU, so the file holds no static initialiser (the table
// below is constant-initialised) and its two kernels are flattened (line_blend.hpp).
#if defined(NETSHAPE_MOTION_AVX2) && defined(__AVX2__)
#include "line_blend.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#define NETSHAPE_LINE_BLEND_ISA avx2
#include "line_blend_kernels.inc"
#undef NETSHAPE_LINE_BLEND_ISA

namespace netshape::motion::detail {
extern const LineBlendKernels avx2_line_blend_kernels;
const LineBlendKernels avx2_line_blend_kernels{&avx2::build, &avx2::freeze, "avx2"};
}  // namespace netshape::motion::detail
#endif
