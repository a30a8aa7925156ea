// All the scene's surfaces, spheres and triangles in one primitive numbering, and the ray
// queries the integrator asks of them.
#pragma once

#include <vector>

#include "bvh.h"
#include "sphere.h"
#include "triangle.h"

namespace glint {

// `list` tests every primitive (smallpt's way); `automatic` picks it for scenes so small that a
// tree costs more than it saves (smallpt's 9 spheres render 1.35-1.5x faster without one, see
// bench/BENCHMARKS.md), else the BVH.
enum class Accelerator { automatic, bvh, list };
inline constexpr uint32_t kListMaxPrimitives = 16;

struct Hit {
    double t = kInfinity;
    uint32_t prim = kNoPrimitive;
    TriangleHit triangle;  // barycentrics, when prim is a triangle
};

// Primitive ids: spheres take 0 .. S-1 in order, triangles S .. S+T-1.
class Geometry {
public:
    Geometry() = default;
    Geometry(std::vector<Sphere> spheres, std::vector<Triangle> triangles,
             Accelerator accelerator = Accelerator::automatic);

    size_t sphere_count() const { return spheres_.size(); }
    size_t triangle_count() const { return triangles_.size(); }
    uint32_t primitive_count() const { return static_cast<uint32_t>(spheres_.size() + triangles_.size()); }
    bool is_sphere(uint32_t prim) const { return prim < spheres_.size(); }
    const Sphere& sphere(uint32_t prim) const { return spheres_[prim]; }
    const Triangle& triangle(uint32_t prim) const { return triangles_[prim - spheres_.size()]; }
    uint32_t triangle_id(size_t triangle_index) const {
        return static_cast<uint32_t>(spheres_.size() + triangle_index);
    }
    const Bvh& bvh() const { return bvh_; }
    // Zero-area triangles (collinear or coincident vertices): kept in the numbering, never hit.
    size_t degenerate_triangles() const { return degenerate_; }
    Accelerator accelerator() const { return accelerator_; }

    // Closest hit in (ray.tmin, ray.tmax]; `self` is the primitive the ray leaves from.
    bool intersect(const Ray& ray, uint32_t self, Hit& hit) const;
    // Whether anything other than `target` blocks the ray in (ray.tmin, ray.tmax].
    bool occluded(const Ray& ray, uint32_t self, uint32_t target = kNoPrimitive) const;
    SurfaceInteraction interaction(const Ray& ray, const Hit& hit) const;

private:
    bool test_closest(uint32_t prim, Ray& ray, uint32_t self, Hit& hit) const;
    bool test_any(uint32_t prim, const Ray& ray, uint32_t self) const;

    std::vector<Sphere> spheres_;
    std::vector<Triangle> triangles_;
    Accelerator accelerator_ = Accelerator::bvh;  // never automatic once built
    Bvh bvh_;
    size_t degenerate_ = 0;
};

}  // namespace glint
