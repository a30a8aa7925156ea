// Spheres: bounds, a numerically careful ray test and the surface point it finds.
#pragma once

#include "base/bounds.h"
#include "shapes/interaction.h"

namespace glint {

struct Sphere {
    Vec3 centre;
    double radius = 1;

    Bounds3 bounds() const {
        return Bounds3{centre - Vec3(radius), centre + Vec3(radius)};
    }
    double area() const { return 4 * kPi * radius * radius; }

    // Nearest t in (ray.tmin, ray.tmax], or false. `from_self` says the ray leaves this sphere's
    // surface: then the root at the origin is the surface being left and only the far root of a
    // ray heading inside counts, which rules out self-intersection exactly.
    bool intersect(const Ray& ray, bool from_self, double& t) const {
        // Haines et al. (Ray Tracing Gems, ch. 7): the discriminant from the ray's closest
        // approach to the centre, and roots in the form that avoids cancellation.
        const Vec3 f = ray.o - centre;
        const double a = dot(ray.d, ray.d);
        const double b = dot(f, ray.d);
        const double closest = length(f - ray.d * (b / a));
        const double disc = a * (radius - closest) * (radius + closest);
        if (disc < 0) return false;
        const double q = -(b + std::copysign(std::sqrt(disc), b));
        if (q == 0) return false;  // grazing the origin itself
        const double lf = length(f);
        const double c = (lf - radius) * (lf + radius);
        const double r0 = c / q, r1 = q / a;
        const double t_near = std::min(r0, r1), t_far = std::max(r0, r1);
        if (from_self) {
            if (b >= 0) return false;
            t = t_far;
        } else {
            t = t_near > ray.tmin ? t_near : t_far;
        }
        return t > ray.tmin && t <= ray.tmax;
    }

    SurfaceInteraction interaction(const Ray& ray, double t, uint32_t prim) const;
};

}  // namespace glint
