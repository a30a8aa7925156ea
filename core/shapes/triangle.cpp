#include "shapes/triangle.h"

#include <algorithm>
#include <array>
#include <cmath>

namespace glint {

SurfaceInteraction Triangle::interaction(const TriangleHit& hit, uint32_t prim) const {
    // Interpolating the vertices, rather than evaluating o + t·d, bounds the error by the
    // vertices' magnitudes only (pbrt-v4: gamma(7) over the weighted vertices).
    const Vec3 w0 = v0 * hit.b0, w1 = v1 * hit.b1, w2 = v2 * hit.b2;
    SurfaceInteraction si;
    si.p = w0 + w1 + w2;
    si.p_error = (abs(w0) + abs(w1) + abs(w2)) * gamma(7);
    si.n = normalize(unnormalized_normal());
    si.b1 = hit.b1;
    si.b2 = hit.b2;
    si.prim = prim;
    return si;
}

}  // namespace glint
