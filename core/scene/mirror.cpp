#include "scene/mirror.h"

namespace glint {

BsdfSample sample_rough_mirror(const Material& m, const Vec3& n, const Vec3& wo, Rng& rng, const double* given) {
    const Ggx ggx{Ggx::alpha_of(m.roughness)};
    const Frame frame = facing_frame(n, wo);
    const Vec3 o = frame.to_local(wo);
    double u1, u2;
    direction_numbers(rng, given, u1, u2);
    if (!(o.z > 0)) return {};
    const Vec3 i = reflect_about(o, ggx.sample_visible(o, u1, u2));
    const MicrofacetReflection r = microfacet_reflection(ggx, o, i);
    if (!(r.pdf > 0)) return {};  // below the surface, or a measure-zero normal
    return {frame.to_world(i), m.albedo * (r.f_cos / r.pdf), r.pdf, mirror_flags(m)};
}

BsdfValue evaluate_mirror(const Material& m, const Vec3& n, const Vec3& wo, const Vec3& wi) {
    const Ggx ggx{Ggx::alpha_of(m.roughness)};
    if (ggx.alpha < Ggx::kSmoothAlpha) return {};
    const Frame frame = facing_frame(n, wo);
    const MicrofacetReflection r = microfacet_reflection(ggx, frame.to_local(wo), frame.to_local(wi));
    return {m.albedo * r.f_cos, r.pdf};
}

}  // namespace glint
