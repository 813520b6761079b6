#pragma once
/// \file isa.hpp
/// Which instruction set netshape's SIMD kernels run with.

namespace netshape {

/// The instruction set of the SIMD kernels in this process: "baseline" (SSE2 on x86-64, or the
/// compiler's default elsewhere), "avx2" or "avx512" — the best one the build has kernels for and the
/// CPU runs, unless the environment variable NETSHAPE_ISA names a lower one. Chosen once per process;
/// every choice computes the same results (docs/simd.md).
const char* kernel_isa() noexcept;

}  // namespace netshape
