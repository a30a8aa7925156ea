// Double to float with a chosen rounding direction, for the single-precision data of the BVH:
// a box rounded outward, or a ray origin rounded up and down, still brackets the exact value.
// Values beyond float's range become infinities instead of undefined behaviour.
#pragma once

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

}  // namespace glint
