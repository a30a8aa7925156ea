#include "scene/material.h"

#include "base/sampling.h"

namespace glint {
namespace {

Vec3 reflect(const Vec3& d, const Vec3& n) { return d - n * (2 * dot(n, d)); }

// smallpt's dielectric: Schlick's Fresnel reflectance `re` of the two directions, or total
// internal reflection (no refracted direction).
struct Dielectric {
    Vec3 reflected, refracted;
    double re = 1;
    bool total_internal = true;
};

Dielectric dielectric(const Material& m, const Vec3& d, const Vec3& n, const Vec3& facing) {
    const bool entering = dot(n, facing) > 0;
    const double eta = entering ? 1 / m.ior : m.ior;  // n_incident / n_transmitted
    const double cos_i = -dot(d, facing);
    const double cos2_t = 1 - eta * eta * (1 - cos_i * cos_i);
    Dielectric out;
    out.reflected = reflect(d, facing);
    if (cos2_t < 0) return out;
    const double cos_t = std::sqrt(cos2_t);
    out.refracted = normalize(d * eta + facing * (eta * cos_i - cos_t));
    const double r0 = ((m.ior - 1) / (m.ior + 1)) * ((m.ior - 1) / (m.ior + 1));
    const double c = 1 - (entering ? cos_i : cos_t);  // the cosine on the outer side
    out.re = r0 + (1 - r0) * c * c * c * c * c;
    out.total_internal = false;
    return out;
}

// Reflection or refraction picked with smallpt's probability P = 1/4 + Re/2 and weighted by
// Re/P or Tr/(1-P); total internal reflection reflects.
BsdfSample sample_glass(const Material& m, const Vec3& d, const Vec3& n, const Vec3& facing, Rng& rng) {
    const Dielectric g = dielectric(m, d, n, facing);
    if (g.total_internal) return {g.reflected, m.albedo, 0, true};
    const double p_reflect = 0.25 + 0.5 * g.re;
    if (rng.uniform() < p_reflect) return {g.reflected, m.albedo * (g.re / p_reflect), 0, true};
    return {g.refracted, m.albedo * ((1 - g.re) / (1 - p_reflect)), 0, true};
}

}  // namespace

BsdfSample sample_diffuse(const Material& m, const Vec3& d, const Vec3& n, double u1, double u2) {
    const Vec3 local = sample_cosine_hemisphere(u1, u2);
    return {Frame::around(dot(n, d) < 0 ? n : -n).to_world(local), m.albedo, local.z / kPi, false};
}

bool split_glass(const Material& m, const Vec3& d, const Vec3& n, BsdfSample& reflected, BsdfSample& refracted) {
    const Dielectric g = dielectric(m, d, n, dot(n, d) < 0 ? n : -n);
    if (g.total_internal) return false;
    reflected = {g.reflected, m.albedo * g.re, 0, true};
    refracted = {g.refracted, m.albedo * (1 - g.re), 0, true};
    return true;
}

BsdfSample sample_bsdf(const Material& m, const Vec3& d, const Vec3& n, Rng& rng) {
    const Vec3 facing = dot(n, d) < 0 ? n : -n;  // the normal on the side the ray came from
    switch (m.type) {
        case MaterialType::diffuse: {
            const double u1 = rng.uniform(), u2 = rng.uniform();
            return sample_diffuse(m, d, n, u1, u2);
        }
        case MaterialType::mirror: return {reflect(d, facing), m.albedo, 0, true};
        case MaterialType::glass: return sample_glass(m, d, n, facing, rng);
    }
    return {};
}

}  // namespace glint
