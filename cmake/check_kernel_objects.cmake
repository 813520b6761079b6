# ctest helper: the wide (avx2, avx512) copies of the SIMD kernels (cmake/NetshapeKernels.cmake) must
# define nothing the linker could share with baseline code — a weak, vague-linkage or unique symbol such
# as an Eigen or std template left out of line — or a CPU without that instruction set could run wide
# code through it. Only the kernel tables and functions of the copy's own namespace may be defined.
# Usage: cmake -DNM=<nm> -DOBJECTS=<list of object files> -P check_kernel_objects.cmake
set(checked 0)
foreach(obj IN LISTS OBJECTS)
  if(NOT obj MATCHES "_kernels_avx(2|512)")
    continue()
  endif()
  math(EXPR checked "${checked} + 1")
  execute_process(COMMAND "${NM}" --defined-only "${obj}" OUTPUT_VARIABLE out RESULT_VARIABLE rc)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "${NM} failed on ${obj}")
  endif()
  string(REGEX MATCHALL "[^\n]* [WVu] [^\n]*" shared "${out}")
  # (DW.ref.__gxx_personality_v0, a data word that exception tables point through, is no code)
  list(FILTER shared EXCLUDE REGEX " DW\\.ref\\.")
  if(shared)
    message(FATAL_ERROR "${obj} defines symbols the linker may share with baseline code:\n${shared}")
  endif()
endforeach()
if(checked EQUAL 0)
  message(FATAL_ERROR "no wide kernel object among OBJECTS: nothing was checked")
endif()
message(STATUS "${checked} wide kernel objects: no weak or unique symbols")
