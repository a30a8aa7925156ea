// Double to float with a chosen rounding direction, for the single-precision data of the BVH:
// a box rounded outward, or a ray origin rounded up and down, still brackets the exact value.
// Values beyond float's range become infinities instead of undefined behaviour.
#pragma once

#include <immintrin.h>

#include <bit>
#include <cstdint>
#include <limits>

namespace glint {

inline float to_float_nearest(double v) {
    constexpr double kMax = std::numeric_limits<float>::max();
    if (v > kMax) return std::numeric_limits<float>::infinity();
    if (v < -kMax) return -std::numeric_limits<float>::infinity();
    return static_cast<float>(v);  // NaN stays NaN
}

// The next float towards +inf (or -inf), for finite or infinite non-NaN f: std::nextafter
// without the library call, as the traversal rounds a ray's limit after every leaf.
inline float float_up(float f) {
    if (f == std::numeric_limits<float>::infinity()) return f;
    if (f == 0) return std::numeric_limits<float>::denorm_min();
    const auto bits = std::bit_cast<uint32_t>(f);
    return std::bit_cast<float>(f > 0 ? bits + 1 : bits - 1);
}
inline float float_down(float f) { return -float_up(-f); }

inline float to_float_down(double v) {
    const float f = to_float_nearest(v);
    return static_cast<double>(f) > v ? float_down(f) : f;
}

inline float to_float_up(double v) {
    const float f = to_float_nearest(v);
    return static_cast<double>(f) < v ? float_up(f) : f;
}

// Four doubles at once, each rounded as to_float_up rounds it (AVX): a ray's setup rounds its
// origin and limits this way.
inline __m128 to_float_up(__m256d v) {
    const __m128 f = _mm256_cvtpd_ps(v);  // to nearest; beyond float's range, to the largest float or inf
    const __m256 below_wide = _mm256_castpd_ps(_mm256_cmp_pd(_mm256_cvtps_pd(f), v, _CMP_LT_OQ));
    const __m128 below = _mm256_castps256_ps128(_mm256_permutevar8x32_ps(below_wide, _mm256_setr_epi32(0, 2, 4, 6, 0, 2, 4, 6)));
    // The next float up: -0 becomes +0 first, then the bits step away from zero for a positive
    // value and towards it for a negative one.
    const __m128i bits = _mm_castps_si128(_mm_andnot_ps(_mm_cmpeq_ps(f, _mm_setzero_ps()), f));
    const __m128i up = _mm_add_epi32(bits, _mm_or_si128(_mm_srai_epi32(bits, 31), _mm_set1_epi32(1)));
    return _mm_blendv_ps(f, _mm_castsi128_ps(up), below);
}
// to_float_up in one instruction: AVX-512's conversion with its rounding direction embedded
// ({ru-sae}: towards +inf, no exception flags). The traversal rounds each hit's distance so, on
// the way to the next box test, one instruction where the AVX rounding takes several. Written in
// assembly, as the intrinsic would need the avx512f target on every function this is inlined
// through; %{ %} escape the braces, which GCC reads as dialect alternatives. Only code that runs on AVX-512 may call it.
inline float to_float_up_avx512(double v) {
    float f;
    asm("vcvtsd2ss %{ru-sae%}, %1, %1, %0" : "=v"(f) : "v"(v));
    return f;
}

inline __m128 to_float_down(__m256d v) {
    const __m256d sign = _mm256_set1_pd(-0.0);
    return _mm_xor_ps(to_float_up(_mm256_xor_pd(v, sign)), _mm_set1_ps(-0.0f));
}

}  // namespace glint
