#include "shapes/triangle.h"

#include <algorithm>
#include <array>
#include <cmath>

namespace glint {

namespace {

// A convex polygon of at most 9 corners: a triangle cut by the six planes of a box.
struct Polygon {
    std::array<Vec3, 9> corners;
    int size = 0;
};

// Sutherland and Hodgman's step: the part of `in` on one side of an axis plane (side +1:
// coordinate >= plane, -1: <= plane). A crossing gets the plane's coordinate exactly.
Polygon clip(const Polygon& in, int axis, double plane, double side) {
    Polygon out;
    for (int i = 0; i < in.size; ++i) {
        const Vec3& a = in.corners[i];
        const Vec3& b = in.corners[(i + 1) % in.size];
        const double da = (a[axis] - plane) * side, db = (b[axis] - plane) * side;
        if (da >= 0) out.corners[out.size++] = a;
        if ((da < 0 && db > 0) || (da > 0 && db < 0)) {
            Vec3 q = a + (b - a) * (da / (da - db));
            q[axis] = plane;
            out.corners[out.size++] = q;
        }
    }
    return out;
}

}  // namespace

Bounds3 Triangle::clipped_bounds(const Bounds3& box) const {
    Polygon p;
    p.corners = {v0, v1, v2};
    p.size = 3;
    for (int a = 0; a < 3 && p.size > 0; ++a) {
        p = clip(p, a, box.lo[a], +1);
        p = clip(p, a, box.hi[a], -1);
    }
    Bounds3 part;
    for (int i = 0; i < p.size; ++i) part.extend(p.corners[i]);
    if (part.empty()) return part;
    // Every corner is a weighted mean of the vertices, so their largest coordinate bounds every
    // corner's; six cuts round each crossing a few times in the 53rd bit of that magnitude.
    // 2^-40 of it is far beyond that error and far below a float unit. The part lies in the box.
    const Vec3 m = max(max(abs(v0), abs(v1)), abs(v2));
    const Vec3 pad{0x1p-40 * std::max({m.x, m.y, m.z})};
    part.lo = max(part.lo - pad, box.lo);
    part.hi = min(part.hi + pad, box.hi);
    return part;
}

Bounds3 Triangle::slab_bounds(int axis, double lower, double upper) const {
    const Vec3* v[3] = {&v0, &v1, &v2};
    Bounds3 part;
    for (int i = 0; i < 3; ++i) {
        const Vec3& a = *v[i];
        const Vec3& b = *v[(i + 1) % 3];
        if (a[axis] >= lower && a[axis] <= upper) part.extend(a);
        // The edge from a to b crosses each plane strictly between its ends at most once.
        for (const double plane : {lower, upper}) {
            if ((a[axis] < plane && plane < b[axis]) || (b[axis] < plane && plane < a[axis])) {
                Vec3 q = a + (b - a) * ((plane - a[axis]) / (b[axis] - a[axis]));
                q[axis] = plane;
                part.extend(q);
            }
        }
    }
    return part;
}

SurfaceInteraction Triangle::interaction(const TriangleHit& hit, uint32_t prim) const {
    // Interpolating the vertices, rather than evaluating o + t·d, bounds the error by the
    // vertices' magnitudes only (pbrt-v4: gamma(7) over the weighted vertices).
    const Vec3 w0 = v0 * hit.b0, w1 = v1 * hit.b1, w2 = v2 * hit.b2;
    SurfaceInteraction si;
    si.p = w0 + w1 + w2;
    si.p_error = (abs(w0) + abs(w1) + abs(w2)) * gamma(7);
    si.n = normalize(unnormalized_normal());
    si.prim = prim;
    return si;
}

}  // namespace glint
