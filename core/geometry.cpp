#include "geometry.h"

namespace glint {

Geometry::Geometry(std::vector<Sphere> spheres, std::vector<Triangle> triangles, Accelerator accelerator)
    : spheres_(std::move(spheres)), triangles_(std::move(triangles)), accelerator_(accelerator) {
    for (const Triangle& t : triangles_) degenerate_ += !(t.area() > 0);
    if (accelerator_ == Accelerator::automatic)
        accelerator_ = primitive_count() <= kListMaxPrimitives ? Accelerator::list : Accelerator::bvh;
    if (accelerator_ != Accelerator::bvh) return;
    std::vector<Bounds3> bounds;
    bounds.reserve(primitive_count());
    for (const Sphere& s : spheres_) bounds.push_back(s.bounds());
    for (const Triangle& t : triangles_)
        // A zero-area triangle can never be hit (its determinant is 0): leave it out.
        bounds.push_back(t.area() > 0 ? t.bounds() : Bounds3{});
    bvh_ = Bvh::build(bounds);
}

// A triangle is flat, so a ray leaving it cannot meet it again; a sphere is told, so that it
// keeps only the far root (see Sphere::intersect).
inline bool Geometry::test_closest(uint32_t prim, Ray& ray, uint32_t self, Hit& hit) const {
    if (is_sphere(prim)) {
        double t;
        if (!spheres_[prim].intersect(ray, prim == self, t)) return false;
        hit.triangle = {};
        hit.t = t;
    } else {
        if (prim == self || !triangle(prim).intersect(ray, hit.triangle)) return false;
        hit.t = hit.triangle.t;
    }
    hit.prim = prim;
    ray.tmax = hit.t;
    return true;
}

inline bool Geometry::test_any(uint32_t prim, const Ray& ray, uint32_t self) const {
    if (is_sphere(prim)) {
        double t;
        return spheres_[prim].intersect(ray, prim == self, t);
    }
    TriangleHit unused;
    return prim != self && triangle(prim).intersect(ray, unused);
}

bool Geometry::intersect(const Ray& ray, uint32_t self, Hit& hit) const {
    if (!is_finite(ray.o) || !is_finite(ray.d)) return false;  // would visit every node for nothing
    Ray r = ray;
    if (accelerator_ == Accelerator::bvh)
        return bvh_.closest(r, [&](uint32_t prim, Ray& rr) { return test_closest(prim, rr, self, hit); });
    bool found = false;
    for (uint32_t prim = 0; prim < primitive_count(); ++prim) found |= test_closest(prim, r, self, hit);
    return found;
}

bool Geometry::occluded(const Ray& ray, uint32_t self, uint32_t target) const {
    if (!is_finite(ray.o) || !is_finite(ray.d)) return false;
    auto blocks = [&](uint32_t prim, const Ray& r) { return prim != target && test_any(prim, r, self); };
    if (accelerator_ == Accelerator::bvh) return bvh_.any(ray, blocks);
    for (uint32_t prim = 0; prim < primitive_count(); ++prim)
        if (blocks(prim, ray)) return true;
    return false;
}

SurfaceInteraction Geometry::interaction(const Ray& ray, const Hit& hit) const {
    if (is_sphere(hit.prim)) return spheres_[hit.prim].interaction(ray, hit.t, hit.prim);
    return triangle(hit.prim).interaction(hit.triangle, hit.prim);
}

}  // namespace glint
