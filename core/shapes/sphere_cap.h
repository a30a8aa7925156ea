// A cap of a sphere: the points c + r·w with 1 - w·axis <= one_minus_cos. Lights that poke
// through an opaque sphere (smallpt's radius-600 light through its radius-1e5 ceiling) are seen
// only through the cap on the viewer's side of that sphere's surface, and sampling that cap
// instead of the whole light is what makes light sampling work there.
#pragma once

#include "base/sampling.h"
#include "shapes/sphere.h"

namespace glint {

struct SphereCap {
    Vec3 axis;                  // unit, from the sphere's centre
    double one_minus_cos = 2;   // 2: the whole sphere
    // A basis about the axis, built once with the cap (it takes a division) rather than for each
    // sample: light sampling on smallpt's box samples one cap at nearly every diffuse vertex.
    Frame frame = Frame::around(axis);

    double area(const Sphere& s) const { return 2 * kPi * s.radius * s.radius * one_minus_cos; }
    bool contains(const Sphere& s, const Vec3& x) const {
        return 1 - dot(x - s.centre, axis) / s.radius <= one_minus_cos;
    }
    // A uniformly distributed unit direction w from the centre into the cap.
    Vec3 sample(double u1, double u2) const {
        const double h = u1 * one_minus_cos, sin_theta = std::sqrt(std::max(0.0, h * (2 - h)));
        const CosSin phi = cos_sin_2pi(u2);
        return normalize(frame.to_world({sin_theta * phi.cos, sin_theta * phi.sin, 1 - h}));
    }

    // The part of `light` inside (or outside) `occluder`, if the two surfaces cross. Widened by
    // far more than its rounding error (≈1e-14 for smallpt's walls) so it never misses a point.
    static bool beside(const Sphere& light, const Sphere& occluder, bool inside, SphereCap& out) {
        const double r = light.radius, big = occluder.radius, d = length(light.centre - occluder.centre);
        if (!(d < big + r && d > std::fabs(big - r))) return false;
        // |x - o|² = d² + r² + 2rd·(w·a), a = (c - o)/d: inside iff w·(-a) > (d² + r² - R²)/(2rd).
        const Vec3 a = (light.centre - occluder.centre) / d;
        out = inside ? SphereCap{-a, (big - d + r) * (big + d - r) / (2 * r * d)}
                     : SphereCap{a, (d + r - big) * (d + r + big) / (2 * r * d)};
        out.one_minus_cos = std::min(2.0, std::max(0.0, out.one_minus_cos) + 1e-9);
        return true;
    }
};

}  // namespace glint
