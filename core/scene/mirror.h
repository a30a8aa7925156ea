// The mirror: smallpt's perfect reflector of `albedo`, and with roughness a GGX conductor with no
// Fresnel term, albedo·D·G / (4 |cos θo| |cos θi|): Cycles' Glossy BSDF (GGX) of the same Color
// and Roughness.
#pragma once

#include "base/rng.h"
#include "scene/bsdf_flags.h"
#include "scene/material.h"
#include "scene/microfacet.h"

namespace glint {

inline BsdfFlags mirror_flags(const Material& m) {
    return {uint8_t(BsdfFlags::reflection | (Ggx::is_smooth(m.roughness) ? BsdfFlags::specular : BsdfFlags::glossy))};
}
// n: the unit geometric normal (either side); wo: toward where the path came from.
// A rough mirror's direction takes two numbers (direction_numbers).
BsdfSample sample_rough_mirror(const Material& m, const Vec3& n, const Vec3& wo, Rng& rng, const double* given);
// A smooth mirror's takes none: smallpt's reflection, inline on the hot path.
inline BsdfSample sample_mirror(const Material& m, const Vec3& n, const Vec3& wo, Rng& rng, const double* given) {
    if (!Ggx::is_smooth(m.roughness)) return sample_rough_mirror(m, n, wo, rng, given);
    const Vec3 d = -wo;  // the incoming ray, as smallpt writes the reflection
    const Vec3 facing = dot(n, d) < 0 ? n : -n;
    return {d - facing * (2 * dot(facing, d)), m.albedo, 0, mirror_flags(m)};
}
BsdfValue evaluate_mirror(const Material& m, const Vec3& n, const Vec3& wo, const Vec3& wi);

}  // namespace glint
