// Warping uniform random numbers into the distributions the renderer samples.
#pragma once

#include <array>

#include "base/math.h"

namespace glint {

// cos 2πu and sin 2πu for u in [0, 1), the angle every sampler here turns, without libm: the
// octant comes from 8u exactly, the angle within it (at most π/4, mirrored in odd octants) goes
// through Taylor series to the 17th and 18th powers, whose first omitted terms are below 1e-19.
// Fewer instructions than libm's sincos, and the same bits on every machine, which libm does
// not promise. Accurate to a few units in the last place (tests/test_sampling.cpp).
struct CosSin {
    double cos, sin;
};

namespace detail {
// 1/n! for n = 0 .. 18, computed by the compiler.
inline constexpr auto kInverseFactorials = [] {
    std::array<double, 19> f{};
    f[0] = 1;
    for (int n = 1; n < 19; ++n) f[size_t(n)] = f[size_t(n - 1)] / n;
    return f;
}();

// The signs of cos and sin in each octant of the turn.
inline constexpr double kCosSign[8] = {1, 1, -1, -1, -1, -1, 1, 1};
inline constexpr double kSinSign[8] = {1, 1, 1, 1, -1, -1, -1, -1};

// cos θ and sin θ for 0 <= θ <= π/4, by Horner's rule in θ².
inline CosSin cos_sin_octant(double theta) {
    const auto& f = kInverseFactorials;
    const double t2 = theta * theta;
    double c = f[18], s = f[17];
    for (int n = 16; n >= 0; n -= 2) c = f[size_t(n)] - t2 * c;
    for (int n = 15; n >= 1; n -= 2) s = f[size_t(n)] - t2 * s;
    return {c, theta * s};
}
}  // namespace detail

inline CosSin cos_sin_2pi(double u) {
    const double v = 8 * u;
    const int octant = static_cast<int>(v) & 7;
    const double t = v - static_cast<int>(v);
    // The octant's symmetry by table look-ups and exact products (odd + ±t is t or 1 - t, a sign
    // times ±1 flips it) rather than a switch, which, on a random octant, mispredicted most of the
    // time: octants 1, 2, 5 and 6 swap the two.
    const double odd = octant & 1;
    const CosSin a = detail::cos_sin_octant((odd + (1 - 2 * odd) * t) * (kPi / 4));
    const double both[2] = {a.cos, a.sin};
    const int swap = ((octant + 1) >> 1) & 1;
    return {detail::kCosSign[octant] * both[swap], detail::kSinSign[octant] * both[swap ^ 1]};
}

// Cosine-weighted direction about +z (Malley's method); pdf = cos θ / π.
inline Vec3 sample_cosine_hemisphere(double u1, double u2) {
    const CosSin phi = cos_sin_2pi(u1);
    const double r = std::sqrt(u2);
    return {r * phi.cos, r * phi.sin, safe_sqrt(1 - u2)};
}

inline Vec3 sample_uniform_sphere(double u1, double u2) {
    const double z = 1 - 2 * u1, r = safe_sqrt(1 - z * z);
    const CosSin phi = cos_sin_2pi(u2);
    return {r * phi.cos, r * phi.sin, z};
}

// Uniform point in the unit disk, polar mapping; for the thin lens.
inline void sample_disk(double u1, double u2, double& x, double& y) {
    const double r = std::sqrt(u1);
    const CosSin phi = cos_sin_2pi(u2);
    x = r * phi.cos;
    y = r * phi.sin;
}

// Barycentric weights of a uniformly distributed point on a triangle.
// The largest double below 1: where a remapped uniform number must stay inside [0, 1).
inline constexpr double kOneMinusEpsilon = 0x1.fffffffffffffp-1;

inline Vec3 sample_uniform_triangle(double u1, double u2) {
    const double s = std::sqrt(u1);
    return {1 - s, s * (1 - u2), s * u2};
}

// smallpt's tent filter: a triangular density on (-1, 1) by inverting its CDF.
inline double sample_tent(double u) {
    const double r = 2 * u;
    return r < 1 ? std::sqrt(r) - 1 : 1 - std::sqrt(2 - r);
}

// Uniform directions in the cone of half-angle θmax around +z, for a sphere of radius r whose
// centre is at distance d (sin²θmax = r²/d²). Every quantity is formed without cancellation so
// a light subtending 1e-12 sr still gets a finite, exact pdf: 1 - cos θmax = sin²θmax / (1 + cos θmax).
struct Cone {
    double sin2_max;
    double one_minus_cos_max;

    static Cone subtended(double radius, double distance) {
        const double sin2 = std::min(1.0, (radius / distance) * (radius / distance));
        return {sin2, sin2 / (1 + safe_sqrt(1 - sin2))};
    }
    double pdf() const { return 1 / (2 * kPi * one_minus_cos_max); }
    // A direction about +z; also returns sin²θ, formed as x(2 - x) with x = 1 - cos θ.
    Vec3 sample(double u1, double u2, double& sin2_theta) const {
        const double x = u1 * one_minus_cos_max;
        sin2_theta = x * (2 - x);
        const double sin_theta = std::sqrt(sin2_theta);
        const CosSin phi = cos_sin_2pi(u2);
        return {sin_theta * phi.cos, sin_theta * phi.sin, 1 - x};
    }
};

// Power heuristic with β = 2 (Veach 1997) for combining two sampling techniques.
inline double power_heuristic(double pdf_a, double pdf_b) {
    const double a = pdf_a * pdf_a, b = pdf_b * pdf_b;
    return a / (a + b);
}

}  // namespace glint
