#pragma once
// netshape's one SIMD vocabulary. Wide packs exist only in kernel translation units
// (cpp/src/<area>/kernels/*.cpp, compiled for their instruction set); elsewhere W = 1 and W = 2 do, so a
// kernel template can also be instantiated one point at a time in ordinary code.
//
// `Batch<W>` is a pack of W doubles (`D`), its lane mask (`M`) and the operations the kernels use:
//
//   W = 1  plain double and bool, any compiler and CPU;
//   W = 2  two doubles (SSE2 on x86-64, a GCC/Clang vector of two elsewhere);
//   W = 4  AVX2 (only in translation units compiled for AVX2 or AVX-512);
//   W = 8  AVX-512F (only in translation units compiled for AVX-512).
//
// `native_width` is the widest pack of the unit being compiled. A kernel is a template over W written
// once; the CMake helper `netshape_add_kernels` compiles each kernel file once per instruction set and
// core/dispatch.hpp picks the copy that runs. For W ≥ 2, D is a GCC/Clang vector type, so + − * / and
// element access d[i] work on it directly as well as through the named functions.
//
// Invariants: no function fuses a multiply and an add (and kernel units compile with
// -ffp-contract=off), so every lane computes what the scalar code computes, bit for bit; `sum` adds the
// lanes in the order stated at each width; `blend(m, a, b)` is m ? b : a lane by lane; `load`/`store`
// with a mask touch only the lanes of the mask (no access past them).
#include <cmath>
#include <cstdint>

#if defined(__SSE2__) || defined(__AVX2__) || defined(__AVX512F__)
// GCC 12 reports the deliberately undefined pass-through operand inside its AVX-512 intrinsics as
// uninitialised (GCC bug 105593); the warning is silenced for the intrinsic headers only, which is why
// kernel files include this header before any other (Eigen includes them too).
#if defined(__GNUC__) && !defined(__clang__)
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wuninitialized"
#pragma GCC diagnostic ignored "-Wmaybe-uninitialized"
#endif
#include <immintrin.h>
#if defined(__GNUC__) && !defined(__clang__)
#pragma GCC diagnostic pop
#endif
#endif

#if defined(__GNUC__)
#define NETSHAPE_SIMD_INLINE inline __attribute__((always_inline))
#define NETSHAPE_SIMD_LAMBDA __attribute__((always_inline))
// Packs are returned from always-inlined functions only; the ABI note about passing wide vectors
// between functions compiled for different ISAs does not apply.
#pragma GCC diagnostic ignored "-Wpsabi"
#else
#define NETSHAPE_SIMD_INLINE inline
#define NETSHAPE_SIMD_LAMBDA
#endif

namespace netshape::simd {

#if defined(__AVX512F__)
inline constexpr int native_width = 8;
#elif defined(__AVX2__)
inline constexpr int native_width = 4;
#elif defined(__GNUC__)
inline constexpr int native_width = 2;
#else
inline constexpr int native_width = 1;
#endif

template <int W>
struct Batch;

/// One lane: plain double arithmetic.
template <>
struct Batch<1> {
  using D = double;
  using M = bool;
  using I = int;  // one int per lane
  static constexpr int W = 1;
  static NETSHAPE_SIMD_INLINE D set(double x) { return x; }
  static NETSHAPE_SIMD_INLINE D iota() { return 0.0; }
  static NETSHAPE_SIMD_INLINE D loadu(const double* p) { return *p; }
  static NETSHAPE_SIMD_INLINE void storeu(double* p, D x) { *p = x; }
  static NETSHAPE_SIMD_INLINE M valid(int n) { return n > 0; }
  static NETSHAPE_SIMD_INLINE D load(const double* p, M, bool) { return *p; }
  static NETSHAPE_SIMD_INLINE void store(double* p, D x, M, bool) { *p = x; }
  static NETSHAPE_SIMD_INLINE double lane(D a, int) { return a; }
  static NETSHAPE_SIMD_INLINE D add(D a, D b) { return a + b; }
  static NETSHAPE_SIMD_INLINE D sub(D a, D b) { return a - b; }
  static NETSHAPE_SIMD_INLINE D mul(D a, D b) { return a * b; }
  static NETSHAPE_SIMD_INLINE D div(D a, D b) { return a / b; }
  static NETSHAPE_SIMD_INLINE D sqrt(D a) { return std::sqrt(a); }
  /// |a|: the sign bit cleared
  static NETSHAPE_SIMD_INLINE D abs(D a) { return std::fabs(a); }
  static NETSHAPE_SIMD_INLINE D floor(D a) { return std::floor(a); }
  static NETSHAPE_SIMD_INLINE D ceil(D a) { return std::ceil(a); }
  static NETSHAPE_SIMD_INLINE D max(D a, D b) { return a > b ? a : b; }
  static NETSHAPE_SIMD_INLINE D min(D a, D b) { return a < b ? a : b; }
  static NETSHAPE_SIMD_INLINE M lt(D a, D b) { return a < b; }
  static NETSHAPE_SIMD_INLINE M le(D a, D b) { return a <= b; }
  static NETSHAPE_SIMD_INLINE M gt(D a, D b) { return a > b; }
  static NETSHAPE_SIMD_INLINE M ge(D a, D b) { return a >= b; }
  static NETSHAPE_SIMD_INLINE M ne(D a, D b) { return a != b; }
  static NETSHAPE_SIMD_INLINE M land(M a, M b) { return a && b; }
  static NETSHAPE_SIMD_INLINE M lor(M a, M b) { return a || b; }
  static NETSHAPE_SIMD_INLINE M lnot(M a) { return !a; }
  static NETSHAPE_SIMD_INLINE bool any(M m) { return m; }
  static NETSHAPE_SIMD_INLINE D blend(M m, D a, D b) { return m ? b : a; }
  static NETSHAPE_SIMD_INLINE int count(M m) { return m ? 1 : 0; }
  /// The lane itself.
  static NETSHAPE_SIMD_INLINE double sum(D a) { return a; }
};

#if defined(__GNUC__)
/// Two lanes: SSE2 on x86-64, a generic GCC/Clang vector elsewhere (element-wise code).
template <>
struct Batch<2> {
  typedef double D __attribute__((vector_size(16)));
  typedef std::int64_t M __attribute__((vector_size(16)));  // all ones or zero per lane
  typedef int I __attribute__((vector_size(8)));            // one int per lane
  static constexpr int W = 2;
  static NETSHAPE_SIMD_INLINE D set(double x) { return D{x, x}; }
  static NETSHAPE_SIMD_INLINE D iota() { return D{0.0, 1.0}; }
  static NETSHAPE_SIMD_INLINE D loadu(const double* p) {
    D v;
    __builtin_memcpy(&v, p, sizeof v);
    return v;
  }
  static NETSHAPE_SIMD_INLINE void storeu(double* p, D x) { __builtin_memcpy(p, &x, sizeof x); }
  static NETSHAPE_SIMD_INLINE M valid(int n) { return M{n > 0 ? -1 : 0, n > 1 ? -1 : 0}; }
  static NETSHAPE_SIMD_INLINE D load(const double* p, M v, bool full) {
    if (full) return loadu(p);
    return D{v[0] ? p[0] : 0.0, v[1] ? p[1] : 0.0};
  }
  static NETSHAPE_SIMD_INLINE void store(double* p, D x, M v, bool full) {
    if (full) return storeu(p, x);
    if (v[0]) p[0] = x[0];
    if (v[1]) p[1] = x[1];
  }
  static NETSHAPE_SIMD_INLINE double lane(D a, int i) { return a[i]; }
  static NETSHAPE_SIMD_INLINE D add(D a, D b) { return a + b; }
  static NETSHAPE_SIMD_INLINE D sub(D a, D b) { return a - b; }
  static NETSHAPE_SIMD_INLINE D mul(D a, D b) { return a * b; }
  static NETSHAPE_SIMD_INLINE D div(D a, D b) { return a / b; }
  static NETSHAPE_SIMD_INLINE D sqrt(D a) {
#if defined(__SSE2__)
    return _mm_sqrt_pd(a);
#else
    return D{std::sqrt(a[0]), std::sqrt(a[1])};
#endif
  }
  static NETSHAPE_SIMD_INLINE D abs(D a) {
#if defined(__SSE2__)
    return _mm_andnot_pd(_mm_set1_pd(-0.0), a);
#else
    return D{std::fabs(a[0]), std::fabs(a[1])};
#endif
  }
  static NETSHAPE_SIMD_INLINE D floor(D a) { return D{std::floor(a[0]), std::floor(a[1])}; }
  static NETSHAPE_SIMD_INLINE D ceil(D a) { return D{std::ceil(a[0]), std::ceil(a[1])}; }
#if defined(__SSE2__)
  // maxpd / minpd are exactly a > b ? a : b / a < b ? a : b (GCC does not always see that in the ternary)
  static NETSHAPE_SIMD_INLINE D max(D a, D b) { return _mm_max_pd(a, b); }
  static NETSHAPE_SIMD_INLINE D min(D a, D b) { return _mm_min_pd(a, b); }
#else
  static NETSHAPE_SIMD_INLINE D max(D a, D b) { return a > b ? a : b; }
  static NETSHAPE_SIMD_INLINE D min(D a, D b) { return a < b ? a : b; }
#endif
  static NETSHAPE_SIMD_INLINE M lt(D a, D b) { return a < b; }
  static NETSHAPE_SIMD_INLINE M le(D a, D b) { return a <= b; }
  static NETSHAPE_SIMD_INLINE M gt(D a, D b) { return a > b; }
  static NETSHAPE_SIMD_INLINE M ge(D a, D b) { return a >= b; }
  static NETSHAPE_SIMD_INLINE M ne(D a, D b) { return a != b; }
  static NETSHAPE_SIMD_INLINE M land(M a, M b) { return a & b; }
  static NETSHAPE_SIMD_INLINE M lor(M a, M b) { return a | b; }
  static NETSHAPE_SIMD_INLINE M lnot(M a) { return ~a; }
  static NETSHAPE_SIMD_INLINE bool any(M m) { return (m[0] | m[1]) != 0; }
  static NETSHAPE_SIMD_INLINE D blend(M m, D a, D b) { return m ? b : a; }
  static NETSHAPE_SIMD_INLINE int count(M m) { return (m[0] != 0) + (m[1] != 0); }
  /// lane 0 + lane 1
  static NETSHAPE_SIMD_INLINE double sum(D a) { return a[0] + a[1]; }
};
#endif

#if defined(__AVX2__)
/// Four lanes, AVX2 (no FMA).
template <>
struct Batch<4> {
  using D = __m256d;
  using M = __m256d;  // all ones or zero per lane
  typedef int I __attribute__((vector_size(16)));  // one int per lane
  static constexpr int W = 4;
  static NETSHAPE_SIMD_INLINE D set(double x) { return _mm256_set1_pd(x); }
  static NETSHAPE_SIMD_INLINE D iota() { return _mm256_set_pd(3, 2, 1, 0); }
  static NETSHAPE_SIMD_INLINE D loadu(const double* p) { return _mm256_loadu_pd(p); }
  static NETSHAPE_SIMD_INLINE void storeu(double* p, D x) { _mm256_storeu_pd(p, x); }
  static NETSHAPE_SIMD_INLINE M valid(int n) {
    return _mm256_castsi256_pd(_mm256_cmpgt_epi64(_mm256_set1_epi64x(n), _mm256_set_epi64x(3, 2, 1, 0)));
  }
  static NETSHAPE_SIMD_INLINE D load(const double* p, M v, bool full) {
    return full ? _mm256_loadu_pd(p) : _mm256_maskload_pd(p, _mm256_castpd_si256(v));
  }
  static NETSHAPE_SIMD_INLINE void store(double* p, D x, M v, bool full) {
    if (full) _mm256_storeu_pd(p, x);
    else _mm256_maskstore_pd(p, _mm256_castpd_si256(v), x);
  }
  static NETSHAPE_SIMD_INLINE double lane(D a, int i) { return a[i]; }
  static NETSHAPE_SIMD_INLINE D add(D a, D b) { return _mm256_add_pd(a, b); }
  static NETSHAPE_SIMD_INLINE D sub(D a, D b) { return _mm256_sub_pd(a, b); }
  static NETSHAPE_SIMD_INLINE D mul(D a, D b) { return _mm256_mul_pd(a, b); }
  static NETSHAPE_SIMD_INLINE D div(D a, D b) { return _mm256_div_pd(a, b); }
  static NETSHAPE_SIMD_INLINE D sqrt(D a) { return _mm256_sqrt_pd(a); }
  static NETSHAPE_SIMD_INLINE D abs(D a) { return _mm256_andnot_pd(_mm256_set1_pd(-0.0), a); }
  static NETSHAPE_SIMD_INLINE D floor(D a) { return _mm256_floor_pd(a); }
  static NETSHAPE_SIMD_INLINE D ceil(D a) { return _mm256_ceil_pd(a); }
  static NETSHAPE_SIMD_INLINE D max(D a, D b) { return _mm256_max_pd(a, b); }  // a > b ? a : b
  static NETSHAPE_SIMD_INLINE D min(D a, D b) { return _mm256_min_pd(a, b); }  // a < b ? a : b
  static NETSHAPE_SIMD_INLINE M lt(D a, D b) { return _mm256_cmp_pd(a, b, _CMP_LT_OQ); }
  static NETSHAPE_SIMD_INLINE M le(D a, D b) { return _mm256_cmp_pd(a, b, _CMP_LE_OQ); }
  static NETSHAPE_SIMD_INLINE M gt(D a, D b) { return _mm256_cmp_pd(a, b, _CMP_GT_OQ); }
  static NETSHAPE_SIMD_INLINE M ge(D a, D b) { return _mm256_cmp_pd(a, b, _CMP_GE_OQ); }
  static NETSHAPE_SIMD_INLINE M ne(D a, D b) { return _mm256_cmp_pd(a, b, _CMP_NEQ_UQ); }
  static NETSHAPE_SIMD_INLINE M land(M a, M b) { return _mm256_and_pd(a, b); }
  static NETSHAPE_SIMD_INLINE M lor(M a, M b) { return _mm256_or_pd(a, b); }
  static NETSHAPE_SIMD_INLINE M lnot(M a) { return _mm256_xor_pd(a, _mm256_castsi256_pd(_mm256_set1_epi64x(-1))); }
  static NETSHAPE_SIMD_INLINE bool any(M m) { return _mm256_movemask_pd(m) != 0; }
  static NETSHAPE_SIMD_INLINE D blend(M m, D a, D b) { return _mm256_blendv_pd(a, b, m); }
  static NETSHAPE_SIMD_INLINE int count(M m) {
    return __builtin_popcount(static_cast<unsigned>(_mm256_movemask_pd(m)));
  }
  /// ((lane 0 + lane 1) + lane 2) + lane 3
  static NETSHAPE_SIMD_INLINE double sum(D a) {
    alignas(32) double t[4];
    _mm256_store_pd(t, a);
    return ((t[0] + t[1]) + t[2]) + t[3];
  }
};
#endif

#if defined(__AVX512F__)
/// Eight lanes, AVX-512F (no FMA); masks are mask registers.
template <>
struct Batch<8> {
  using D = __m512d;
  using M = __mmask8;
  typedef int I __attribute__((vector_size(32)));  // one int per lane
  static constexpr int W = 8;
  static NETSHAPE_SIMD_INLINE D set(double x) { return _mm512_set1_pd(x); }
  static NETSHAPE_SIMD_INLINE D iota() { return _mm512_set_pd(7, 6, 5, 4, 3, 2, 1, 0); }
  static NETSHAPE_SIMD_INLINE D loadu(const double* p) { return _mm512_loadu_pd(p); }
  static NETSHAPE_SIMD_INLINE void storeu(double* p, D x) { _mm512_storeu_pd(p, x); }
  static NETSHAPE_SIMD_INLINE M valid(int n) { return n >= 8 ? M(0xFF) : M((1u << (n > 0 ? n : 0)) - 1u); }
  static NETSHAPE_SIMD_INLINE D load(const double* p, M v, bool full) {
    return full ? _mm512_loadu_pd(p) : _mm512_maskz_loadu_pd(v, p);
  }
  static NETSHAPE_SIMD_INLINE void store(double* p, D x, M v, bool full) {
    if (full) _mm512_storeu_pd(p, x);
    else _mm512_mask_storeu_pd(p, v, x);
  }
  static NETSHAPE_SIMD_INLINE double lane(D a, int i) { return a[i]; }
  static NETSHAPE_SIMD_INLINE D add(D a, D b) { return _mm512_add_pd(a, b); }
  static NETSHAPE_SIMD_INLINE D sub(D a, D b) { return _mm512_sub_pd(a, b); }
  static NETSHAPE_SIMD_INLINE D mul(D a, D b) { return _mm512_mul_pd(a, b); }
  static NETSHAPE_SIMD_INLINE D div(D a, D b) { return _mm512_div_pd(a, b); }
  static NETSHAPE_SIMD_INLINE D sqrt(D a) { return _mm512_sqrt_pd(a); }
  static NETSHAPE_SIMD_INLINE D abs(D a) { return _mm512_abs_pd(a); }
  static NETSHAPE_SIMD_INLINE D floor(D a) { return _mm512_roundscale_pd(a, _MM_FROUND_TO_NEG_INF | _MM_FROUND_NO_EXC); }
  static NETSHAPE_SIMD_INLINE D ceil(D a) { return _mm512_roundscale_pd(a, _MM_FROUND_TO_POS_INF | _MM_FROUND_NO_EXC); }
  static NETSHAPE_SIMD_INLINE D max(D a, D b) { return _mm512_max_pd(a, b); }  // a > b ? a : b
  static NETSHAPE_SIMD_INLINE D min(D a, D b) { return _mm512_min_pd(a, b); }  // a < b ? a : b
  static NETSHAPE_SIMD_INLINE M lt(D a, D b) { return _mm512_cmp_pd_mask(a, b, _CMP_LT_OQ); }
  static NETSHAPE_SIMD_INLINE M le(D a, D b) { return _mm512_cmp_pd_mask(a, b, _CMP_LE_OQ); }
  static NETSHAPE_SIMD_INLINE M gt(D a, D b) { return _mm512_cmp_pd_mask(a, b, _CMP_GT_OQ); }
  static NETSHAPE_SIMD_INLINE M ge(D a, D b) { return _mm512_cmp_pd_mask(a, b, _CMP_GE_OQ); }
  static NETSHAPE_SIMD_INLINE M ne(D a, D b) { return _mm512_cmp_pd_mask(a, b, _CMP_NEQ_UQ); }
  static NETSHAPE_SIMD_INLINE M land(M a, M b) { return M(a & b); }
  static NETSHAPE_SIMD_INLINE M lor(M a, M b) { return M(a | b); }
  static NETSHAPE_SIMD_INLINE M lnot(M a) { return M(~a & 0xFF); }
  static NETSHAPE_SIMD_INLINE bool any(M m) { return m != 0; }
  static NETSHAPE_SIMD_INLINE D blend(M m, D a, D b) { return _mm512_mask_blend_pd(m, a, b); }
  static NETSHAPE_SIMD_INLINE int count(M m) { return __builtin_popcount(m); }
  /// The tree order of _mm512_reduce_add_pd: halves of 256, then of 128 bits, then the last two.
  static NETSHAPE_SIMD_INLINE double sum(D a) { return _mm512_reduce_add_pd(a); }
};
#endif

/// The lanes of a folded left to right into m with std::min's semantics (m = a_i < m ? a_i : m: a lane
/// replaces m only when smaller, so a NaN lane leaves it, and of equal values m stays).
template <int W>
NETSHAPE_SIMD_INLINE double fold_min(typename Batch<W>::D a, double m) noexcept {
  alignas(64) double l[W];
  Batch<W>::storeu(l, a);
  for (int i = 0; i < W; ++i) m = l[i] < m ? l[i] : m;
  return m;
}
/// The same with std::max's semantics (m = m < a_i ? a_i : m).
template <int W>
NETSHAPE_SIMD_INLINE double fold_max(typename Batch<W>::D a, double m) noexcept {
  alignas(64) double l[W];
  Batch<W>::storeu(l, a);
  for (int i = 0; i < W; ++i) m = m < l[i] ? l[i] : m;
  return m;
}

/// Hint that the cache line at p will be written soon (no-op where the compiler has no prefetch).
NETSHAPE_SIMD_INLINE void prefetch_for_write(const double* p) noexcept {
#if defined(__GNUC__)
  __builtin_prefetch(p, 1, 3);
#else
  (void)p;
#endif
}

/// Hint that the n doubles from p on will be written soon: one prefetch per 64-byte line, and the last.
NETSHAPE_SIMD_INLINE void prefetch_span_for_write(const double* p, int n) noexcept {
  for (int k = 0; k < n; k += 8) prefetch_for_write(p + k);
  prefetch_for_write(p + n - 1);
}

}  // namespace netshape::simd

// The namespace of the kernel copy being compiled (baseline, avx2 or avx512), set by the CMake helper.
#define NETSHAPE_SIMD_STR2(x) #x
#define NETSHAPE_SIMD_STR(x) NETSHAPE_SIMD_STR2(x)
/// "baseline", "avx2" or "avx512": the copy being compiled (kernel files only).
#define NETSHAPE_KERNEL_ISA_NAME NETSHAPE_SIMD_STR(NETSHAPE_KERNEL_ISA)
