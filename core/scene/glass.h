// Glass: smallpt's smooth dielectric, and with roughness Walter et al. 2007's rough dielectric
// over GGX, the Fresnel term taken at the microfacet normal. Both tint reflection and
// transmission by `albedo`, pick between them with smallpt's probability 1/4 + F/2, and leave
// radiance unscaled by η² across the surface, as smallpt does: a rough surface's estimate tends
// to the smooth one's as its roughness does, and sampling from the light side gives the adjoint
// weights. `fresnel` is Schlick's with the cosine on the outer side (smallpt's) or the exact one.
#pragma once

#include "base/rng.h"
#include "scene/bsdf_flags.h"
#include "scene/material.h"
#include "scene/microfacet.h"

namespace glint {

inline BsdfFlags glass_flags(const Material& m) {
    return {uint8_t(BsdfFlags::reflection | BsdfFlags::transmission |
                    (Ggx::is_smooth(m.roughness) ? BsdfFlags::specular : BsdfFlags::glossy))};
}
// n: the unit outward geometric normal; wo: toward where the path came from. A rough surface's
// microfacet normal takes two numbers (direction_numbers), then the choice between reflection
// and refraction one of rng; smooth glass takes only the choice, and none under total internal
// reflection.
BsdfSample sample_glass(const Material& m, const Vec3& n, const Vec3& wo, Rng& rng, const double* given);
BsdfValue evaluate_glass(const Material& m, const Vec3& n, const Vec3& wo, const Vec3& wi);
// Smooth glass split into both continuations, each weighted by its Fresnel factor (Re and 1 - Re),
// instead of picking one: false for rough glass, and under total internal reflection, where
// there is one continuation.
bool split_glass(const Material& m, const Vec3& n, const Vec3& wo, BsdfSample& reflected, BsdfSample& refracted);

}  // namespace glint
