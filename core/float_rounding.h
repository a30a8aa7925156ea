// Double to float with a chosen rounding direction, for the single-precision data of the BVH:
// a box rounded outward, or a ray origin rounded up and down, still brackets the exact value.
// Values beyond float's range become infinities instead of undefined behaviour.
#pragma once

#include <cmath>
#include <limits>

namespace glint {

inline float to_float_nearest(double v) {
    constexpr double kMax = std::numeric_limits<float>::max();
    if (v > kMax) return std::numeric_limits<float>::infinity();
    if (v < -kMax) return -std::numeric_limits<float>::infinity();
    return static_cast<float>(v);  // NaN stays NaN
}

inline float to_float_down(double v) {
    const float f = to_float_nearest(v);
    return static_cast<double>(f) > v ? std::nextafter(f, -std::numeric_limits<float>::infinity()) : f;
}

inline float to_float_up(double v) {
    const float f = to_float_nearest(v);
    return static_cast<double>(f) < v ? std::nextafter(f, std::numeric_limits<float>::infinity()) : f;
}

}  // namespace glint
