// Warping uniform random numbers into the distributions the renderer samples.
#pragma once

#include "math.h"

namespace glint {

// Cosine-weighted direction about +z (Malley's method); pdf = cos θ / π.
inline Vec3 sample_cosine_hemisphere(double u1, double u2) {
    const double phi = 2 * kPi * u1, r = std::sqrt(u2);
    return {r * std::cos(phi), r * std::sin(phi), safe_sqrt(1 - u2)};
}

inline Vec3 sample_uniform_sphere(double u1, double u2) {
    const double z = 1 - 2 * u1, r = safe_sqrt(1 - z * z), phi = 2 * kPi * u2;
    return {r * std::cos(phi), r * std::sin(phi), z};
}

// Uniform point in the unit disk, polar mapping; for the thin lens.
inline void sample_disk(double u1, double u2, double& x, double& y) {
    const double r = std::sqrt(u1), phi = 2 * kPi * u2;
    x = r * std::cos(phi);
    y = r * std::sin(phi);
}

// Barycentric weights of a uniformly distributed point on a triangle.
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
        const double sin_theta = std::sqrt(sin2_theta), phi = 2 * kPi * u2;
        return {sin_theta * std::cos(phi), sin_theta * std::sin(phi), 1 - x};
    }
};

// Power heuristic with β = 2 (Veach 1997) for combining two sampling techniques.
inline double power_heuristic(double pdf_a, double pdf_b) {
    const double a = pdf_a * pdf_a, b = pdf_b * pdf_b;
    return a / (a + b);
}

}  // namespace glint
