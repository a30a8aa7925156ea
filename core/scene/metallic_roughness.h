// Metal and plastic: glTF 2.0's metallic-roughness model. `metal` is its conductor, a GGX
// specular lobe with Schlick's Fresnel of F0 = albedo; `plastic` its dielectric, a Lambertian
// albedo under a GGX specular layer of index `ior`, combined as glTF's fresnel_mix: the specular
// weighted by F (Schlick's with F0 from ior, at the half vector), the diffuse by what the layer
// lets through. glTF's reference weighs the diffuse by 1 - F at the half vector too, which at
// grazing angles returns up to 1.9 times the light that arrives (the white furnace in
// tests/core/scene/test_bsdf.cpp shows it); here the diffuse is weighted by
// (1 - F(cos θo))·(1 - F(cos θi)), what the layer lets through on the way in and on the way
// out: reciprocal, never more than arrives, and within 4% of glTF's near the normal.
// `metallic` mixes the two linearly; metal is metallic 1 and plastic 0 unless a scene says
// otherwise, so a glTF material (and, with textures, a texel) maps onto one glint material.
// Below Ggx::kSmoothAlpha the specular lobe is a mirror reflection.
#pragma once

#include "base/rng.h"
#include "scene/bsdf_flags.h"
#include "scene/material.h"
#include "scene/microfacet.h"

namespace glint {

inline BsdfFlags metallic_roughness_flags(const Material& m) {
    uint8_t bits = BsdfFlags::reflection | (Ggx::is_smooth(m.roughness) ? BsdfFlags::specular : BsdfFlags::glossy);
    if (m.metallic < 1 && !is_black(m.albedo)) bits |= BsdfFlags::diffuse;
    return {bits};
}
// n: the unit geometric normal (either side; both are the same surface); wo: toward where the
// path came from. Takes one number of rng for the lobe, then two for the direction
// (direction_numbers).
BsdfSample sample_metallic_roughness(const Material& m, const Vec3& n, const Vec3& wo, Rng& rng, const double* given);
BsdfValue evaluate_metallic_roughness(const Material& m, const Vec3& n, const Vec3& wo, const Vec3& wi);

}  // namespace glint
