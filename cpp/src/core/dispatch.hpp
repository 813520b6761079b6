#pragma once
// Run-time choice of the instruction set of netshape's SIMD kernels (private to the library).
//
// Every hand-vectorised loop lives in a kernel translation unit, cpp/src/<area>/kernels/*.cpp, which
// the CMake helper `netshape_add_kernels` (cmake/NetshapeKernels.cmake) compiles once per instruction
// set: `baseline` (what the compiler targets by default: SSE2 on x86-64), and on x86-64 with GCC or
// Clang also `avx2` and `avx512` (AVX-512F). Each copy defines its entry points as a constant table of
// function pointers in the namespace named after its ISA; the library picks one table per process:
//
//     // kernels/ramp.hpp                          // the caller
//     struct RampKernels { void (*move)(...); };   static const RampKernels& k =
//     NETSHAPE_SIMD_DECLARE(RampKernels, ramp)         NETSHAPE_SIMD_SELECT(kernels, ramp);
//
// Invariants: the tables are constant-initialised (no code of a wide ISA runs before the CPU has been
// checked); kernel files define no symbol the linker could share with baseline code (checked by the
// ctest `cpp_kernel_objects`); kernel files compile without FMA contraction, so every copy of a
// kernel computes the same bits unless its documentation says where lane count changes a sum's order.
#include <cstdint>

namespace netshape::simd {

/// Instruction sets the kernels are compiled for, lowest first.
enum class Isa : std::uint8_t { baseline = 0, avx2 = 1, avx512 = 2 };

/// "baseline", "avx2" or "avx512".
const char* isa_name(Isa isa) noexcept;
/// The best instruction set this build has kernels for and this CPU (and OS) runs.
Isa cpu_isa() noexcept;
/// The instruction set the kernels run with: cpu_isa(), or lower when the environment variable
/// NETSHAPE_ISA names a lower one (baseline|avx2|avx512; for tests and benchmarks). A name above what
/// the CPU runs is lowered to cpu_isa(); an unknown name is reported once on stderr and ignored.
/// Read once per process.
Isa active_isa() noexcept;
/// True when this build has kernels for `isa` and the CPU runs them.
bool runs(Isa isa) noexcept;

/// The table for `isa`, falling back to the next lower one that exists (null entries are missing).
template <class Table>
const Table& select(const Table& baseline, const Table* avx2, const Table* avx512, Isa isa) noexcept {
  if (isa == Isa::avx512 && avx512 != nullptr) return *avx512;
  if (isa >= Isa::avx2 && avx2 != nullptr) return *avx2;
  return baseline;
}

}  // namespace netshape::simd

// NETSHAPE_SIMD_X86 is defined (by CMake, for the whole library) when the avx2 and avx512 kernel copies
// are built.
#if defined(NETSHAPE_SIMD_X86)
#define NETSHAPE_SIMD_DECLARE(Type, name)   \
  namespace baseline {                      \
  extern const Type name;                   \
  }                                         \
  namespace avx2 {                          \
  extern const Type name;                   \
  }                                         \
  namespace avx512 {                        \
  extern const Type name;                   \
  }
/// The kernel table `name` of namespace `ns` for instruction set `isa`.
#define NETSHAPE_SIMD_SELECT_ISA(ns, name, isa) \
  ::netshape::simd::select(ns::baseline::name, &ns::avx2::name, &ns::avx512::name, isa)
#else
#define NETSHAPE_SIMD_DECLARE(Type, name) \
  namespace baseline {                    \
  extern const Type name;                 \
  }
#define NETSHAPE_SIMD_SELECT_ISA(ns, name, isa)                                                     \
  ::netshape::simd::select(ns::baseline::name, static_cast<decltype(&ns::baseline::name)>(nullptr), \
                           static_cast<decltype(&ns::baseline::name)>(nullptr), isa)
#endif
/// The kernel table `name` of namespace `ns` for the active instruction set.
#define NETSHAPE_SIMD_SELECT(ns, name) NETSHAPE_SIMD_SELECT_ISA(ns, name, ::netshape::simd::active_isa())
