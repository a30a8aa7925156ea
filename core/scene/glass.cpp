#include "scene/glass.h"

#include "scene/fresnel.h"
#include "scene/microfacet.h"

namespace glint {
namespace {

bool is_smooth(const Material& m) { return Ggx::is_smooth(m.roughness); }

// The reflectance of light meeting the interface at cosine cos_i (> 0) and refracted at cos_t,
// eta the index of the near side over the far side's, `entering` from the outside.
[[gnu::always_inline]] inline double reflectance(const Material& m, double cos_i, double cos_t, double eta,
                                                 bool entering) {
    if (m.fresnel == FresnelModel::exact) return fresnel_dielectric(cos_i, 1 / eta);
    const double r0 = dielectric_f0(m.ior);
    const double c = 1 - (entering ? cos_i : cos_t);  // the cosine on the outer side
    return r0 + (1 - r0) * c * c * c * c * c;  // smallpt's order of products (fresnel.h's rounds otherwise)
}

// smallpt's choice between reflection and refraction, reflectance re.
double reflect_probability(double re) { return 0.25 + 0.5 * re; }

// The smooth dielectric: the reflectance `re` of the two directions, or total internal
// reflection (no refracted direction). d: the incoming ray; facing: the normal on its side.
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
    out.reflected = d - facing * (2 * dot(facing, d));
    if (cos2_t < 0) return out;
    const double cos_t = std::sqrt(cos2_t);
    out.refracted = normalize(d * eta + facing * (eta * cos_i - cos_t));
    out.re = reflectance(m, cos_i, cos_t, eta, entering);
    out.total_internal = false;
    return out;
}

BsdfSample sample_smooth(const Material& m, const Vec3& n, const Vec3& wo, Rng& rng) {
    const Vec3 d = -wo;
    const Dielectric g = dielectric(m, d, n, dot(n, d) < 0 ? n : -n);
    const BsdfFlags flags = glass_flags(m);
    if (g.total_internal) return {g.reflected, m.albedo, 0, flags};
    const double p_reflect = reflect_probability(g.re);
    if (rng.uniform() < p_reflect) return {g.reflected, m.albedo * (g.re / p_reflect), 0, flags};
    return {g.refracted, m.albedo * ((1 - g.re) / (1 - p_reflect)), 0, flags};
}

// The rough dielectric in the local frame of the side wo lies on: o.z > 0, and eta the index of
// that side over the other's.
struct RoughSide {
    Frame frame;
    Vec3 o;
    double eta;
    bool entering;
};

RoughSide rough_side(const Material& m, const Vec3& n, const Vec3& wo) {
    const bool entering = dot(n, wo) > 0;
    const Frame frame = Frame::around(entering ? n : -n);
    return {frame, frame.to_local(wo), entering ? 1 / m.ior : m.ior, entering};
}

// What happens at microfacet normal h seen from o: the reflectance (1 under total internal
// reflection), the refracted cosine, and smallpt's probability of reflecting.
struct AtNormal {
    double cos_o, cos_t = 0, re = 1, p_reflect = 1;
    bool total_internal = true;
};

AtNormal at_normal(const Material& m, const RoughSide& side, const Vec3& h) {
    AtNormal a{dot(side.o, h)};
    const double cos2_t = 1 - side.eta * side.eta * (1 - a.cos_o * a.cos_o);
    if (cos2_t < 0) return a;
    a.cos_t = std::sqrt(cos2_t);
    a.re = reflectance(m, a.cos_o, a.cos_t, side.eta, side.entering);
    a.p_reflect = reflect_probability(a.re);
    a.total_internal = false;
    return a;
}

// Rough transmission from o to i (i.z < 0), as f·|cos θi| and the pdf of sampling it.
BsdfValue rough_transmission(const Material& m, const Ggx& ggx, const RoughSide& side, const Vec3& i) {
    // The generalised half vector: refraction about h gives i = -η·o + (η·o·h - cos θt)·h, so
    // η·o + i lies along h, turned away from it where η < 1 (entering the denser side).
    const Vec3 along = side.o * side.eta + i;
    const double len2 = dot(along, along);
    if (!(len2 > 0)) return {};  // index 1: straight through, a direction of measure zero
    const Vec3 h = along * ((side.eta < 1 ? -1 : 1) / std::sqrt(len2));
    const double cos_ih = dot(i, h);
    const AtNormal a = at_normal(m, side, h);
    // Refracted through the microfacet, but out on wo's side of the surface: no path.
    if (!(a.cos_o > 0) || !(cos_ih < 0) || !(i.z < 0) || a.total_internal) return {};
    // dω_h / dω_i = |i·h| / (i·h + o·h·η)² with η the near index over the far one.
    const double denom = cos_ih + a.cos_o * side.eta;
    const double jacobian = -cos_ih / (denom * denom);
    const double visible = ggx.visible_pdf(side.o, h);
    return {m.albedo * ((1 - a.re) * visible * jacobian * ggx.g1(i)), (1 - a.p_reflect) * visible * jacobian};
}

BsdfValue rough_reflection(const Material& m, const Ggx& ggx, const RoughSide& side, const Vec3& i) {
    const MicrofacetReflection r = microfacet_reflection(ggx, side.o, i);
    if (!(r.pdf > 0)) return {};
    const AtNormal a = at_normal(m, side, r.h);
    return {m.albedo * (a.re * r.f_cos), a.p_reflect * r.pdf};
}

BsdfSample sample_rough(const Material& m, const Vec3& n, const Vec3& wo, Rng& rng, const double* given) {
    const Ggx ggx{Ggx::alpha_of(m.roughness)};
    const RoughSide side = rough_side(m, n, wo);
    double u1, u2;
    direction_numbers(rng, given, u1, u2);
    if (!(side.o.z > 0)) return {};
    const Vec3 h = ggx.sample_visible(side.o, u1, u2);
    const AtNormal a = at_normal(m, side, h);
    const bool reflect = a.total_internal || rng.uniform() < a.p_reflect;
    const Vec3 i = reflect ? reflect_about(side.o, h)
                           : -side.o * side.eta + h * (side.eta * a.cos_o - a.cos_t);
    const BsdfValue v = reflect ? rough_reflection(m, ggx, side, i) : rough_transmission(m, ggx, side, i);
    if (!(v.pdf > 0) || !is_finite(v.f_cos)) return {};
    return {side.frame.to_world(i), v.f_cos / v.pdf, v.pdf, glass_flags(m)};
}

}  // namespace

BsdfSample sample_glass(const Material& m, const Vec3& n, const Vec3& wo, Rng& rng, const double* given) {
    return is_smooth(m) ? sample_smooth(m, n, wo, rng) : sample_rough(m, n, wo, rng, given);
}

BsdfValue evaluate_glass(const Material& m, const Vec3& n, const Vec3& wo, const Vec3& wi) {
    if (is_smooth(m)) return {};
    const Ggx ggx{Ggx::alpha_of(m.roughness)};
    const RoughSide side = rough_side(m, n, wo);
    if (!(side.o.z > 0)) return {};
    const Vec3 i = side.frame.to_local(wi);
    if (i.z > 0) return rough_reflection(m, ggx, side, i);
    if (i.z < 0) return rough_transmission(m, ggx, side, i);
    return {};
}

bool split_glass(const Material& m, const Vec3& n, const Vec3& wo, BsdfSample& reflected, BsdfSample& refracted) {
    if (!is_smooth(m)) return false;
    const Vec3 d = -wo;
    const Dielectric g = dielectric(m, d, n, dot(n, d) < 0 ? n : -n);
    if (g.total_internal) return false;
    reflected = {g.reflected, m.albedo * g.re, 0, glass_flags(m)};
    refracted = {g.refracted, m.albedo * (1 - g.re), 0, glass_flags(m)};
    return true;
}

}  // namespace glint
