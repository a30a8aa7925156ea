#include "material.h"

#include "sampling.h"

namespace glint {
namespace {

Vec3 reflect(const Vec3& d, const Vec3& n) { return d - n * (2 * dot(n, d)); }

BsdfSample sample_diffuse(const Material& m, const Vec3& facing, Rng& rng) {
    const double u1 = rng.uniform(), u2 = rng.uniform();
    const Vec3 local = sample_cosine_hemisphere(u1, u2);
    return {Frame::around(facing).to_world(local), m.albedo, local.z / kPi, false};
}

// smallpt's dielectric: Schlick's Fresnel, then reflection or refraction picked with
// probability P = 1/4 + Re/2 and weighted by Re/P or Tr/(1-P); total internal reflection reflects.
BsdfSample sample_glass(const Material& m, const Vec3& d, const Vec3& n, const Vec3& facing, Rng& rng) {
    const bool entering = dot(n, facing) > 0;
    const double eta = entering ? 1 / m.ior : m.ior;  // n_incident / n_transmitted
    const double cos_i = -dot(d, facing);
    const double cos2_t = 1 - eta * eta * (1 - cos_i * cos_i);
    const Vec3 reflected = reflect(d, facing);
    if (cos2_t < 0) return {reflected, m.albedo, 0, true};

    const double cos_t = std::sqrt(cos2_t);
    const Vec3 refracted = normalize(d * eta + facing * (eta * cos_i - cos_t));
    const double r0 = ((m.ior - 1) / (m.ior + 1)) * ((m.ior - 1) / (m.ior + 1));
    const double c = 1 - (entering ? cos_i : cos_t);  // the cosine on the outer side
    const double re = r0 + (1 - r0) * c * c * c * c * c;
    const double p_reflect = 0.25 + 0.5 * re;
    if (rng.uniform() < p_reflect) return {reflected, m.albedo * (re / p_reflect), 0, true};
    return {refracted, m.albedo * ((1 - re) / (1 - p_reflect)), 0, true};
}

}  // namespace

BsdfSample sample_bsdf(const Material& m, const Vec3& d, const Vec3& n, Rng& rng) {
    const Vec3 facing = dot(n, d) < 0 ? n : -n;  // the normal on the side the ray came from
    switch (m.type) {
        case MaterialType::diffuse: return sample_diffuse(m, facing, rng);
        case MaterialType::mirror: return {reflect(d, facing), m.albedo, 0, true};
        case MaterialType::glass: return sample_glass(m, d, n, facing, rng);
    }
    return {};
}

}  // namespace glint
