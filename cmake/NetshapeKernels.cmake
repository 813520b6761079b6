# netshape_add_kernels(<target>): compile every kernel file cpp/src/<area>/kernels/*.cpp once per
# instruction set and add the objects to <target> (the netshape library).
#
#   baseline  the compiler's default target (SSE2 on x86-64); always built
#   avx2      -mavx2                 x86-64 with GCC or Clang only
#   avx512    -mavx512f -mfma        x86-64 with GCC or Clang only (every AVX-512F CPU has FMA;
#                                    Eigen requires the flag, -ffp-contract=off keeps it unused)
#
# Each copy is compiled with NETSHAPE_KERNEL_ISA=<isa> (the namespace its entry points go into; see
# cpp/src/core/dispatch.hpp) and the kernel flags below; nothing else in the library gets them, so a
# function keeps its floating-point semantics wherever it is moved outside kernels/. When the wide copies
# are built, NETSHAPE_SIMD_X86 is defined for the whole library.
#
# Kernel flags, the same for every copy:
#   -ffp-contract=off              no fused multiply-add: every copy computes the same bits
#   -fno-math-errno                sqrt and friends inline to one instruction (no errno is read)
#   -fno-trapping-math, -fno-rounding-math   no FP exception or rounding mode is read or changed
#   -fopenmp-simd                  `#pragma omp simd` loops (no OpenMP runtime)
#   -O3 (except Debug builds)      the kernels are the hot loops whatever the build type
include_guard(GLOBAL)

function(netshape_add_kernels target)
  file(GLOB kernel_sources CONFIGURE_DEPENDS ${PROJECT_SOURCE_DIR}/cpp/src/*/kernels/*.cpp)
  if(NOT kernel_sources)
    return()
  endif()
  set(isas baseline)
  if(CMAKE_CXX_COMPILER_ID MATCHES "GNU|Clang" AND CMAKE_SYSTEM_PROCESSOR MATCHES "^(x86_64|AMD64|amd64)$")
    list(APPEND isas avx2 avx512)
    target_compile_definitions(${target} PRIVATE NETSHAPE_SIMD_X86=1)
  endif()
  set(isa_flag_baseline "")
  set(isa_flag_avx2 -mavx2)
  set(isa_flag_avx512 -mavx512f -mfma)  # (Eigen refuses AVX-512 without FMA; contraction stays off)
  foreach(isa IN LISTS isas)
    set(obj ${target}_kernels_${isa})
    add_library(${obj} OBJECT ${kernel_sources})
    set_target_properties(${obj} PROPERTIES POSITION_INDEPENDENT_CODE ON CXX_EXTENSIONS OFF)
    target_compile_features(${obj} PRIVATE cxx_std_17)
    target_link_libraries(${obj} PRIVATE Eigen3::Eigen)
    # the library's include directories, definitions and compile options (warnings, sanitizers)
    target_include_directories(${obj} PRIVATE $<TARGET_PROPERTY:${target},INCLUDE_DIRECTORIES>)
    target_compile_definitions(${obj} PRIVATE $<TARGET_PROPERTY:${target},COMPILE_DEFINITIONS>
                                              NETSHAPE_KERNEL_ISA=${isa})
    target_compile_options(${obj} PRIVATE $<TARGET_PROPERTY:${target},COMPILE_OPTIONS>)
    if(CMAKE_CXX_COMPILER_ID MATCHES "GNU|Clang")
      target_compile_options(${obj} PRIVATE ${isa_flag_${isa}} -ffp-contract=off -fno-math-errno
                             -fno-trapping-math -fopenmp-simd $<$<NOT:$<CONFIG:Debug>>:-O3>)
      if(CMAKE_CXX_COMPILER_ID STREQUAL "GNU")
        target_compile_options(${obj} PRIVATE -fno-rounding-math -fvect-cost-model=dynamic)
      endif()
    endif()
    target_sources(${target} PRIVATE $<TARGET_OBJECTS:${obj}>)
  endforeach()
endfunction()
