// A point on a surface with a bound on its rounding error, and rays spawned from it.
#pragma once

#include "base/ray.h"

namespace glint {

struct SurfaceInteraction {
    Vec3 p;        // the hit point as computed
    Vec3 p_error;  // per-axis bound on |p - exact point|
    Vec3 n;        // unit geometric normal: outward for spheres, right-handed winding for triangles
    // Where `shaded`, the unit shading normal a mesh's vertex normals or a normal map give, on
    // n's side (scene/shading_normal.h says how the BSDF uses it); elsewhere unset and never read,
    // as are b1 and b2 off triangles: a record filled on every hit pays only for what it uses.
    Vec3 ns;
    bool shaded = false;
    double b1, b2;  // a triangle's barycentric weights of v1 and v2, for its attributes
    uint32_t prim = kNoPrimitive;

    const Vec3& shading_normal() const { return shaded ? ns : n; }
};

// Moves p off the surface, to the side that w points to, by just more than its error bound
// (pbrt-v4's OffsetRayOrigin): far enough that the new origin is provably on that side, and no
// further, so a second surface a hair away is still found. No scene-scale epsilon is involved.
inline Vec3 offset_ray_origin(const SurfaceInteraction& si, const Vec3& w) {
    const double d = dot(abs(si.n), si.p_error);
    Vec3 offset = si.n * d;
    if (dot(w, si.n) < 0) offset = -offset;
    Vec3 po = si.p + offset;
    for (int a = 0; a < 3; ++a) {
        if (offset[a] > 0) po[a] = next_up(po[a]);
        else if (offset[a] < 0) po[a] = next_down(po[a]);
    }
    return po;
}

inline Ray spawn_ray(const SurfaceInteraction& si, const Vec3& w) {
    return Ray{offset_ray_origin(si, w), w};
}

}  // namespace glint
