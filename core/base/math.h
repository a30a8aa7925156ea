// Vectors, constants and floating-point helpers shared by every part of the renderer.
// glint computes in double: smallpt's radius-1e5 walls are seen from ~100 units away, and
// double keeps hit points, offsets and sums honest without per-scene tuning.
#pragma once

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>

namespace glint {

inline constexpr double kPi = 3.14159265358979323846;
inline constexpr double kInfinity = std::numeric_limits<double>::infinity();

struct Vec3 {
    double x = 0, y = 0, z = 0;

    constexpr Vec3() = default;
    constexpr Vec3(double x_, double y_, double z_) : x(x_), y(y_), z(z_) {}
    constexpr explicit Vec3(double v) : x(v), y(v), z(v) {}

    constexpr double operator[](int i) const { return i == 0 ? x : (i == 1 ? y : z); }
    constexpr double& operator[](int i) { return i == 0 ? x : (i == 1 ? y : z); }

    constexpr Vec3 operator+(const Vec3& b) const { return {x + b.x, y + b.y, z + b.z}; }
    constexpr Vec3 operator-(const Vec3& b) const { return {x - b.x, y - b.y, z - b.z}; }
    constexpr Vec3 operator-() const { return {-x, -y, -z}; }
    constexpr Vec3 operator*(double s) const { return {x * s, y * s, z * s}; }
    constexpr Vec3 operator/(double s) const { return {x / s, y / s, z / s}; }
    // Component-wise product: colours times colours, as smallpt's Vec::mult.
    constexpr Vec3 operator*(const Vec3& b) const { return {x * b.x, y * b.y, z * b.z}; }
    constexpr Vec3& operator+=(const Vec3& b) { x += b.x; y += b.y; z += b.z; return *this; }
    constexpr Vec3& operator*=(const Vec3& b) { x *= b.x; y *= b.y; z *= b.z; return *this; }
    constexpr Vec3& operator*=(double s) { x *= s; y *= s; z *= s; return *this; }
    constexpr bool operator==(const Vec3&) const = default;
};

// Radiance and albedo are RGB triples with the same arithmetic.
using Rgb = Vec3;

constexpr Vec3 operator*(double s, const Vec3& v) { return v * s; }
constexpr double dot(const Vec3& a, const Vec3& b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
constexpr Vec3 cross(const Vec3& a, const Vec3& b) {
    return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}
inline double length(const Vec3& v) { return std::sqrt(dot(v, v)); }
inline Vec3 normalize(const Vec3& v) { return v / length(v); }
inline Vec3 abs(const Vec3& v) { return {std::fabs(v.x), std::fabs(v.y), std::fabs(v.z)}; }
constexpr Vec3 min(const Vec3& a, const Vec3& b) {
    return {std::min(a.x, b.x), std::min(a.y, b.y), std::min(a.z, b.z)};
}
constexpr Vec3 max(const Vec3& a, const Vec3& b) {
    return {std::max(a.x, b.x), std::max(a.y, b.y), std::max(a.z, b.z)};
}
constexpr double max_component(const Vec3& v) { return std::max(v.x, std::max(v.y, v.z)); }
constexpr double min_component(const Vec3& v) { return std::min(v.x, std::min(v.y, v.z)); }
inline int max_axis(const Vec3& v) { return v.x > v.y ? (v.x > v.z ? 0 : 2) : (v.y > v.z ? 1 : 2); }
inline bool is_finite(const Vec3& v) {
    return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}
constexpr bool is_black(const Rgb& c) { return c.x == 0 && c.y == 0 && c.z == 0; }
constexpr double luminance(const Rgb& c) { return 0.2126 * c.x + 0.7152 * c.y + 0.0722 * c.z; }

// Higham's bound on the relative error of n successive roundings: |error| <= gamma(n)·|value|.
constexpr double gamma(int n) {
    constexpr double eps = std::numeric_limits<double>::epsilon() * 0.5;
    return (n * eps) / (1 - n * eps);
}

// The neighbouring doubles, by stepping the bit pattern (as pbrt-v4's NextFloatUp): inline and
// branch-light, where std::nextafter is a libm call (5% of a Cornell render's instructions).
inline double next_up(double v) {
    if (!(v < kInfinity)) return v;  // +∞ and NaN
    if (v == 0) v = 0.0;  // -0 steps up like +0
    uint64_t bits = std::bit_cast<uint64_t>(v);
    bits = v >= 0 ? bits + 1 : bits - 1;
    return std::bit_cast<double>(bits);
}
inline double next_down(double v) { return -next_up(-v); }

// sqrt that treats tiny negative rounding results as 0 instead of returning NaN.
inline double safe_sqrt(double v) { return std::sqrt(std::max(0.0, v)); }

// An orthonormal basis around a unit vector n (Duff et al. 2017, "Building an orthonormal
// basis, revisited"): branch-free and continuous except on one half-plane.
struct Frame {
    Vec3 s, t, n;
    static Frame around(const Vec3& n) {
        const double sign = std::copysign(1.0, n.z);
        const double a = -1.0 / (sign + n.z);
        const double b = n.x * n.y * a;
        return {{1 + sign * n.x * n.x * a, sign * b, -sign * n.x}, {b, sign + n.y * n.y * a, -n.y}, n};
    }
    Vec3 to_world(const Vec3& v) const { return s * v.x + t * v.y + n * v.z; }
    Vec3 to_local(const Vec3& v) const { return {dot(v, s), dot(v, t), dot(v, n)}; }
};

}  // namespace glint
