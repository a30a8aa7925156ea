// Spheres without a tree (smallpt's way, and faster than a tree for a handful of them), tested
// four at a time in AVX double. Each lane performs Sphere::intersect's operations in the same
// order, and IEEE arithmetic rounds each the same in a lane as in a scalar register (no fused
// multiply-add: the build has -ffp-contract=off), so every t, and so every answer, is the scalar
// test's bit for bit; only the loop around it is cheaper.
#pragma once

#include <vector>

#include "base/ray.h"
#include "shapes/sphere.h"

namespace glint {

class SphereList {
public:
    SphereList() = default;
    explicit SphereList(const std::vector<Sphere>& spheres);

    // The sphere of the nearest hit in (ray.tmin, ray.tmax], its t in `t`, or -1. Of equal
    // nearest hits the last sphere wins, as a scalar loop narrowing tmax with `<=` decides.
    // `self` is the index of the sphere the ray leaves (or any value past the end).
    int closest(const Ray& ray, uint32_t self, double& t) const;
    // Whether a sphere other than `target` is hit in (ray.tmin, ray.tmax].
    bool any(const Ray& ray, uint32_t self, uint32_t target) const;

private:
    // Four spheres, coordinate by coordinate; lanes past the last sphere have a NaN radius,
    // which never hits.
    struct alignas(32) Group {
        double cx[4], cy[4], cz[4], radius[4];
    };
    std::vector<Group> groups_;
};

}  // namespace glint
