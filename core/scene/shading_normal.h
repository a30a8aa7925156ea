// How a BSDF uses a shading normal (vertex normals interpolated, or a normal map) without
// leaking light through the surface or blackening it where the geometry does not.
//
// Two published rules, as Cycles applies them:
// - The shading normal is bent, where it must be, so that the mirror direction of wo about it
//   lies above the geometric surface (Keller et al. 2017, "The Iray Light Transport Simulation
//   and Rendering System", appendix A.3; Cycles' ensure_valid_reflection). Without it, a view
//   direction below the shading normal but above the facet (a coarse mesh's silhouette) finds
//   every lobe on the far side and the pixel goes black.
// - A direction counts only where the geometric normal agrees with the shading normal about
//   whether it is a reflection or a transmission (Veach 1997, §5.3; pbrt-v3's BSDF::f): light
//   never arrives from below the geometric surface of an opaque material.
#pragma once

#include <algorithm>
#include <cmath>

#include "base/math.h"

namespace glint {

// ns on ng's side, bent for wo as above (ng, ns, wo unit vectors).
inline Vec3 shading_normal(const Vec3& ng, const Vec3& ns, const Vec3& wo) {
    const bool front = dot(wo, ng) >= 0;
    const Vec3 g = front ? ng : -ng, s = front ? ns : -ns;  // both on wo's side
    const double cos_g = dot(wo, g);
    const Vec3 r = s * (2 * dot(wo, s)) - wo;
    // The lowest the mirror direction may lie: a little above the surface, or just under wo.
    const double floor = std::min(0.9 * cos_g, 0.01);
    if (dot(r, g) >= floor) return ns;
    // The direction at that height in the plane of g and r, and the normal that mirrors wo there.
    Vec3 across = r - g * dot(r, g);
    if (!(dot(across, across) > 0)) across = g * dot(wo, g) - wo;  // r along -g: away from wo
    const double across_length = length(across);
    if (!(across_length > 0)) return ng;
    const Vec3 target = across * (safe_sqrt(1 - floor * floor) / across_length) + g * floor;
    const Vec3 h = wo + target;
    const double h_length = length(h);
    if (!(h_length > 0)) return ng;
    return front ? h / h_length : -h / h_length;
}

// Whether wi is on the side of the geometric normal ng that the shading normal ns puts it on,
// as seen from wo: both reflections or both transmissions.
inline bool sides_agree(const Vec3& ng, const Vec3& ns, const Vec3& wo, const Vec3& wi) {
    return (dot(wo, ng) * dot(wi, ng) > 0) == (dot(wo, ns) * dot(wi, ns) > 0);
}

}  // namespace glint
