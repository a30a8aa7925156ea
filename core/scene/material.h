// What a surface does with light: smallpt's three materials, plus emission on any primitive.
#pragma once

#include "base/math.h"
#include "base/rng.h"

namespace glint {

enum class MaterialType { diffuse, mirror, glass };

struct Material {
    MaterialType type = MaterialType::diffuse;
    Rgb albedo{0.75};
    double ior = 1.5;
    Rgb emission{0};  // radiance leaving both sides of the surface

    bool is_emissive() const { return !is_black(emission); }
};

// One sampled continuation of a path: the new direction, the factor f·cos/pdf by which the
// path's throughput is multiplied, and the solid-angle pdf (for MIS; 0 for specular lobes).
struct BsdfSample {
    Vec3 wi;
    Rgb weight;
    double pdf = 0;
    bool specular = false;
};

// d: the incoming ray's direction; n: the unit geometric normal (either side).
BsdfSample sample_bsdf(const Material& m, const Vec3& d, const Vec3& n, Rng& rng);
// Cosine-weighted reflection from (u1, u2) in [0, 1)², on the side d came from.
BsdfSample sample_diffuse(const Material& m, const Vec3& d, const Vec3& n, double u1, double u2);
// Glass split into both continuations, each weighted by its Fresnel factor (Re and 1 - Re),
// instead of picking one: false under total internal reflection, where there is one.
bool split_glass(const Material& m, const Vec3& d, const Vec3& n, BsdfSample& reflected, BsdfSample& refracted);

// Lambertian reflection f·cos for light arriving along wi at a surface hit from direction d
// (0 when wi is on the other side), and the pdf with which sample_bsdf would pick wi.
inline Rgb diffuse_f_cos(const Material& m, const Vec3& d, const Vec3& n, const Vec3& wi, double& pdf) {
    const double cos_out = -dot(d, n), cos_in = dot(wi, n);
    if (cos_out * cos_in <= 0) {
        pdf = 0;
        return Rgb{0};
    }
    pdf = std::fabs(cos_in) / kPi;
    return m.albedo * pdf;
}

}  // namespace glint
