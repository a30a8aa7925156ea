// Lambertian reflection: f = albedo / π on the side the path arrives from, sampled by the cosine.
#pragma once

#include "base/sampling.h"
#include "scene/bsdf_flags.h"
#include "scene/material.h"

namespace glint {

inline constexpr BsdfFlags kLambertianFlags{BsdfFlags::diffuse | BsdfFlags::reflection};

// n: the unit geometric normal (either side); wo: toward where the path came from.
inline BsdfSample sample_lambertian(const Material& m, const Vec3& n, const Vec3& wo, double u1, double u2) {
    const Vec3 local = sample_cosine_hemisphere(u1, u2);
    return {Frame::around(dot(n, wo) > 0 ? n : -n).to_world(local), m.albedo, local.z / kPi, kLambertianFlags};
}

inline BsdfValue evaluate_lambertian(const Material& m, const Vec3& n, const Vec3& wo, const Vec3& wi) {
    const double cos_out = dot(wo, n), cos_in = dot(wi, n);
    if (cos_out * cos_in <= 0) return {};
    const double pdf = std::fabs(cos_in) / kPi;
    return {m.albedo * pdf, pdf};
}

}  // namespace glint
