// The GGX (Trowbridge-Reitz) microfacet distribution, isotropic, with the separable Smith
// masking-shadowing G = G1(wo)·G1(wi) (glTF 2.0's reference BRDF and Cycles' GGX), sampled from
// its distribution of visible normals (Heitz 2018, "Sampling the GGX Distribution of Visible
// Normals"). Directions are local: +z is the normal of the side the distribution faces; every
// form here avoids the cancellation of 1 - cos² near the normal.
#pragma once

#include "base/math.h"
#include "base/sampling.h"

namespace glint {

struct Ggx {
    // Below this α (roughness r below 0.0316) a surface is handled as smooth: its microfacet
    // normals then stray from the surface's by about α radians (0.06°), so the switch leaves no
    // seam (a test renders r = 0.035 within noise of r = 0), and the delta lobe's estimator has
    // no noise at all.
    static constexpr double kSmoothAlpha = 1e-3;

    double alpha;

    static double alpha_of(double roughness) { return roughness * roughness; }
    // Whether a surface of this roughness is handled as smooth.
    static bool is_smooth(double roughness) { return alpha_of(roughness) < kSmoothAlpha; }

    // D(h), for h.z > 0 (0 elsewhere).
    double d(const Vec3& h) const {
        if (!(h.z > 0)) return 0;
        const double a2 = alpha * alpha;
        const double e = (h.x * h.x + h.y * h.y) / a2 + h.z * h.z;
        return 1 / (kPi * a2 * e * e);
    }
    // Smith's masking for direction w, on either side: 2 / (1 + sqrt(1 + α² tan² θ)).
    double g1(const Vec3& w) const {
        const double z2 = w.z * w.z;
        if (!(z2 > 0)) return 0;
        const double a2_tan2 = alpha * alpha * (w.x * w.x + w.y * w.y) / z2;
        return 2 / (1 + std::sqrt(1 + a2_tan2));
    }
    // Density of the visible normal h seen from wo (wo.z > 0): G1(wo)·max(0, wo·h)·D(h) / wo.z.
    double visible_pdf(const Vec3& wo, const Vec3& h) const {
        const double cos_oh = dot(wo, h);
        if (!(cos_oh > 0) || !(wo.z > 0)) return 0;
        return g1(wo) * cos_oh * d(h) / wo.z;
    }
    // A normal drawn with density visible_pdf(wo, ·), for wo.z > 0.
    Vec3 sample_visible(const Vec3& wo, double u1, double u2) const {
        const Vec3 v = normalize(Vec3{alpha * wo.x, alpha * wo.y, wo.z});  // the hemisphere configuration
        const double len2 = v.x * v.x + v.y * v.y;
        const Vec3 t1 = len2 > 0 ? Vec3{-v.y, v.x, 0} / std::sqrt(len2) : Vec3{1, 0, 0};
        const Vec3 t2 = cross(v, t1);
        // A uniform point on the disc, its lower half squeezed toward the projected hemisphere's rim.
        const double r = std::sqrt(u1);
        const CosSin phi = cos_sin_2pi(u2);
        const double p1 = r * phi.cos, s = 0.5 * (1 + v.z);
        const double p2 = (1 - s) * safe_sqrt(1 - p1 * p1) + s * r * phi.sin;
        const Vec3 nh = t1 * p1 + t2 * p2 + v * safe_sqrt(1 - p1 * p1 - p2 * p2);
        return normalize(Vec3{alpha * nh.x, alpha * nh.y, std::max(0.0, nh.z)});
    }
};

// Microfacet reflection from wo to wi (both local, z > 0), before its Fresnel factor: f·cos θi =
// D·G1(wo)·G1(wi) / (4 cos θo), and the density with which reflecting wo about a visible normal
// picks wi, G1(wo)·D / (4 cos θo). Also the half vector, for the Fresnel factor.
struct MicrofacetReflection {
    double f_cos = 0, pdf = 0;
    Vec3 h;
};

inline MicrofacetReflection microfacet_reflection(const Ggx& ggx, const Vec3& wo, const Vec3& wi) {
    MicrofacetReflection r;
    if (!(wo.z > 0) || !(wi.z > 0)) return r;
    const Vec3 sum = wo + wi;
    const double len2 = dot(sum, sum);
    if (!(len2 > 0)) return r;
    r.h = sum / std::sqrt(len2);
    const double d = ggx.d(r.h), g1o = ggx.g1(wo);
    r.pdf = g1o * d / (4 * wo.z);
    r.f_cos = r.pdf * ggx.g1(wi);
    return r;
}

// The local frame of the side of the surface (unit normal n, either side) that wo lies on.
inline Frame facing_frame(const Vec3& n, const Vec3& wo) { return Frame::around(dot(n, wo) > 0 ? n : -n); }

// wo mirrored about h.
inline Vec3 reflect_about(const Vec3& wo, const Vec3& h) { return h * (2 * dot(wo, h)) - wo; }

}  // namespace glint
