#include "scene/metallic_roughness.h"

#include "base/sampling.h"
#include "scene/fresnel.h"
#include "scene/microfacet.h"

namespace glint {
namespace {

bool is_smooth(const Material& m) { return Ggx::is_smooth(m.roughness); }

// The specular layer's colour at cosine c: the dielectric's F and the conductor's, mixed.
Rgb specular_colour(const Material& m, double c) {
    return Rgb{(1 - m.metallic) * schlick(dielectric_f0(m.ior), c)} + schlick(m.albedo, c) * m.metallic;
}

// The diffuse base's reflectance seen from cosine c, what the dielectric's specular layer lets
// through on that side.
Rgb diffuse_colour(const Material& m, double c) {
    return m.albedo * ((1 - m.metallic) * (1 - schlick(dielectric_f0(m.ior), c)));
}

// The probability of sampling the specular lobe, from the two lobes' weights seen from cos θo;
// each keeps at least a tenth where both are present, so that neither goes unsampled where the
// estimate is off at grazing angles.
double specular_probability(const Material& m, double cos_o) {
    const double s = luminance(specular_colour(m, cos_o)), d = luminance(diffuse_colour(m, cos_o));
    if (!(d > 0)) return 1;
    if (!(s > 0)) return 0;
    return std::clamp(s / (s + d), 0.1, 0.9);
}

// Both lobes from o to i, local (o.z > 0): f·cos θi and the pdf of sampling i.
BsdfValue evaluate_local(const Material& m, const Vec3& o, const Vec3& i) {
    if (!(o.z > 0) || !(i.z > 0)) return {};
    const double p_specular = specular_probability(m, o.z);
    const Vec3 h = normalize(o + i);
    const double c = dot(o, h), cos_pdf = i.z / kPi;
    const double coat_in = 1 - schlick(dielectric_f0(m.ior), i.z);  // the layer crossed on the way in
    BsdfValue v{diffuse_colour(m, o.z) * (coat_in * cos_pdf), (1 - p_specular) * cos_pdf};
    if (is_smooth(m)) return v;
    const MicrofacetReflection r = microfacet_reflection(Ggx{Ggx::alpha_of(m.roughness)}, o, i);
    v.f_cos += specular_colour(m, c) * r.f_cos;
    v.pdf += p_specular * r.pdf;
    return v;
}

}  // namespace

BsdfSample sample_metallic_roughness(const Material& m, const Vec3& n, const Vec3& wo, Rng& rng,
                                     const double* given) {
    const Frame frame = facing_frame(n, wo);
    const Vec3 o = frame.to_local(wo);
    const double u_lobe = rng.uniform();
    double u1, u2;
    direction_numbers(rng, given, u1, u2);
    if (!(o.z > 0)) return {};
    const double p_specular = specular_probability(m, o.z);
    const bool specular = u_lobe < p_specular;
    if (specular && is_smooth(m)) {
        const BsdfFlags flags{BsdfFlags::reflection | BsdfFlags::specular};
        return {frame.to_world({-o.x, -o.y, o.z}), specular_colour(m, o.z) / p_specular, 0, flags};
    }
    const Ggx ggx{Ggx::alpha_of(m.roughness)};
    const Vec3 i = specular ? reflect_about(o, ggx.sample_visible(o, u1, u2)) : sample_cosine_hemisphere(u1, u2);
    const BsdfValue v = evaluate_local(m, o, i);
    if (!(v.pdf > 0)) return {};
    const BsdfFlags flags{uint8_t(BsdfFlags::reflection | (specular ? BsdfFlags::glossy : BsdfFlags::diffuse))};
    return {frame.to_world(i), v.f_cos / v.pdf, v.pdf, flags};
}

BsdfValue evaluate_metallic_roughness(const Material& m, const Vec3& n, const Vec3& wo, const Vec3& wi) {
    const Frame frame = facing_frame(n, wo);
    return evaluate_local(m, frame.to_local(wo), frame.to_local(wi));
}

}  // namespace glint
