// The run-time choice of the kernels' instruction set (core/dispatch.hpp).
#include "core/dispatch.hpp"

#include "netshape/core/isa.hpp"

#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <initializer_list>

namespace netshape::simd {

const char* isa_name(Isa isa) noexcept {
  switch (isa) {
    case Isa::avx512: return "avx512";
    case Isa::avx2: return "avx2";
    case Isa::baseline:
    default: return "baseline";
  }
}

Isa cpu_isa() noexcept {
  static const Isa best = [] {
#if defined(NETSHAPE_SIMD_X86)
    __builtin_cpu_init();
    if (__builtin_cpu_supports("avx512f")) return Isa::avx512;
    if (__builtin_cpu_supports("avx2")) return Isa::avx2;
#endif
    return Isa::baseline;
  }();
  return best;
}

bool runs(Isa isa) noexcept { return isa <= cpu_isa(); }

Isa active_isa() noexcept {
  static const Isa chosen = [] {
    const Isa best = cpu_isa();
    const char* env = std::getenv("NETSHAPE_ISA");
    if (env == nullptr || *env == '\0') return best;
    for (Isa want : {Isa::baseline, Isa::avx2, Isa::avx512})
      if (std::strcmp(env, isa_name(want)) == 0) return want < best ? want : best;
    std::fprintf(stderr, "netshape: NETSHAPE_ISA='%s' is not one of baseline, avx2, avx512; using %s\n", env,
                 isa_name(best));
    return best;
  }();
  return chosen;
}

}  // namespace netshape::simd

const char* netshape::kernel_isa() noexcept { return simd::isa_name(simd::active_isa()); }
