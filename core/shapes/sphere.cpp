#include "shapes/sphere.h"

namespace glint {

SurfaceInteraction Sphere::interaction(const Ray& ray, double t, uint32_t prim) const {
    // Re-project the computed point onto the sphere: whatever error t carried, the point is then
    // on the surface up to the rounding of these few operations (pbrt-v4's bound, 5 roundings),
    // plus one for adding the centre back.
    Vec3 local = ray.o + ray.d * t - centre;
    local *= radius / length(local);
    SurfaceInteraction si;
    si.p = centre + local;
    si.p_error = abs(local) * gamma(5) + abs(si.p) * gamma(1);
    si.n = local / radius;
    si.prim = prim;
    return si;
}

}  // namespace glint
