// What kinds of scattering a BSDF has, and what one sampled continuation is: the vocabulary the
// integrator and its strategies use instead of asking which material they hit.
#pragma once

#include <cstdint>

#include "base/math.h"
#include "base/rng.h"

namespace glint {

struct BsdfFlags {
    enum : uint8_t { reflection = 1, transmission = 2, diffuse = 4, glossy = 8, specular = 16 };
    uint8_t bits = 0;

    bool has(uint8_t b) const { return (bits & b) != 0; }
    // Every lobe a Dirac delta (smooth mirror, glass, metal): no light sampling, no MIS.
    bool is_specular() const { return has(specular) && !has(diffuse | glossy); }
    // Lambertian reflection alone: the vertices light paths and their connections are made of,
    // whose densities mis.h's weights assume (cosine sampling everywhere).
    bool is_diffuse() const { return bits == (diffuse | reflection); }
};

// One sampled continuation of a path: the new direction, the factor f·|cos|/pdf by which the
// path's throughput is multiplied, the solid-angle pdf (0 for a specular lobe), and the lobe's
// kind. A weight of 0 is a failed sample: the path ends.
struct BsdfSample {
    Vec3 wi;
    Rgb weight;
    double pdf = 0;
    BsdfFlags flags;

    bool is_specular() const { return flags.has(BsdfFlags::specular); }
};

// f·|cos θi| and the pdf with which sampling would pick wi (both 0 where f is).
struct BsdfValue {
    Rgb f_cos{0};
    double pdf = 0;
};

// The two numbers a sampled direction takes: `given` (a stratified pair) if not null, else the
// next two of rng.
inline void direction_numbers(Rng& rng, const double* given, double& u1, double& u2) {
    if (given) {
        u1 = given[0];
        u2 = given[1];
    } else {
        u1 = rng.uniform();
        u2 = rng.uniform();
    }
}

}  // namespace glint
