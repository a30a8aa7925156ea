#include "geometry.h"

namespace glint {

Geometry::Geometry(std::vector<Sphere> spheres, const std::vector<Triangle>& triangles, Accelerator accelerator)
    : spheres_(std::move(spheres)), accelerator_(accelerator) {
    std::vector<PackedTriangle> packed;
    std::vector<Bounds3> triangle_bounds;
    packed.reserve(triangles.size());
    triangle_bounds.reserve(triangles.size());
    for (const Triangle& input : triangles) {
        packed.push_back(PackedTriangle::pack(input));
        const Triangle t = packed.back().unpack();
        // A zero-area triangle can never be hit (its determinant is 0): leave it out of the tree.
        const bool degenerate = !(t.area() > 0);
        degenerate_ += degenerate;
        triangle_bounds.push_back(degenerate ? Bounds3{} : t.bounds());
    }
    if (accelerator_ == Accelerator::automatic)
        accelerator_ = spheres_.size() + packed.size() <= kListMaxPrimitives ? Accelerator::list : Accelerator::bvh;
    if (accelerator_ != Accelerator::bvh) {
        triangles_ = std::move(packed);
        return;
    }
    std::vector<Bounds3> sphere_bounds;
    sphere_bounds.reserve(spheres_.size());
    for (const Sphere& s : spheres_) sphere_bounds.push_back(s.bounds());
    sphere_bvh_ = Bvh::build(sphere_bounds);

    triangle_bvh_ = Bvh::build(triangle_bounds);
    triangle_at_ = triangle_bvh_.order();
    position_of_.resize(packed.size());
    triangles_.reserve(packed.size());
    for (uint32_t pos = 0; pos < triangle_at_.size(); ++pos) {
        position_of_[triangle_at_[pos]] = pos;
        triangles_.push_back(packed[triangle_at_[pos]]);
    }
}

size_t Geometry::memory_bytes() const {
    return sphere_bvh_.memory_bytes() + sphere_bvh_.order().size() * sizeof(uint32_t) + triangle_bvh_.memory_bytes() +
           triangles_.size() * sizeof(PackedTriangle) + (triangle_at_.size() + position_of_.size()) * sizeof(uint32_t);
}

uint32_t Geometry::position(uint32_t prim) const {
    if (prim < spheres_.size() || prim - spheres_.size() >= triangles_.size()) return kNoPrimitive;
    const auto index = static_cast<uint32_t>(prim - spheres_.size());
    return position_of_.empty() ? index : position_of_[index];
}

// A triangle is flat, so a ray leaving it cannot meet it again; a sphere is told, so that it
// keeps only the far root (see Sphere::intersect).
bool Geometry::closest_triangle(Ray& ray, uint32_t self, Hit& hit) const {
    const uint32_t skip = position(self);
    const RayShear shear(ray);
    auto test = [&](uint32_t pos, Ray& r) {
        if (pos == skip || !triangles_[pos].intersect(r, shear, hit.triangle)) return false;
        hit.t = r.tmax = hit.triangle.t;
        hit.prim = triangle_id(triangle_at_.empty() ? pos : triangle_at_[pos]);
        return true;
    };
    if (accelerator_ == Accelerator::bvh) return triangle_bvh_.closest(ray, test);
    bool found = false;
    for (uint32_t pos = 0; pos < triangles_.size(); ++pos) found |= test(pos, ray);
    return found;
}

bool Geometry::closest_sphere(Ray& ray, uint32_t self, Hit& hit) const {
    if (spheres_.empty()) return false;  // a mesh scene pays nothing for spheres
    auto test = [&](uint32_t prim, Ray& r) {
        double t;
        if (!spheres_[prim].intersect(r, prim == self, t)) return false;
        hit = {t, prim, {}};
        r.tmax = t;
        return true;
    };
    if (accelerator_ == Accelerator::bvh)
        return sphere_bvh_.closest(ray, [&](uint32_t pos, Ray& r) { return test(sphere_bvh_.order()[pos], r); });
    bool found = false;
    for (uint32_t prim = 0; prim < spheres_.size(); ++prim) found |= test(prim, ray);
    return found;
}

bool Geometry::intersect(const Ray& ray, uint32_t self, Hit& hit) const {
    if (!is_finite(ray.o) || !is_finite(ray.d)) return false;  // would visit every node for nothing
    Ray r = ray;
    const bool triangle_hit = closest_triangle(r, self, hit);
    return closest_sphere(r, self, hit) || triangle_hit;
}

bool Geometry::triangle_blocks(const Ray& ray, uint32_t self, uint32_t target) const {
    const uint32_t skip = position(self), wanted = position(target);
    const RayShear shear(ray);
    auto blocks = [&](uint32_t pos, const Ray& r) {
        TriangleHit unused;
        return pos != skip && pos != wanted && triangles_[pos].intersect(r, shear, unused);
    };
    if (accelerator_ == Accelerator::bvh) return triangle_bvh_.any(ray, blocks);
    for (uint32_t pos = 0; pos < triangles_.size(); ++pos)
        if (blocks(pos, ray)) return true;
    return false;
}

bool Geometry::sphere_blocks(const Ray& ray, uint32_t self, uint32_t target) const {
    if (spheres_.empty()) return false;
    auto blocks = [&](uint32_t prim, const Ray& r) {
        double t;
        return prim != target && spheres_[prim].intersect(r, prim == self, t);
    };
    if (accelerator_ == Accelerator::bvh)
        return sphere_bvh_.any(ray, [&](uint32_t pos, const Ray& r) { return blocks(sphere_bvh_.order()[pos], r); });
    for (uint32_t prim = 0; prim < spheres_.size(); ++prim)
        if (blocks(prim, ray)) return true;
    return false;
}

bool Geometry::occluded(const Ray& ray, uint32_t self, uint32_t target) const {
    if (!is_finite(ray.o) || !is_finite(ray.d)) return false;
    return sphere_blocks(ray, self, target) || triangle_blocks(ray, self, target);
}

SurfaceInteraction Geometry::interaction(const Ray& ray, const Hit& hit) const {
    if (is_sphere(hit.prim)) return spheres_[hit.prim].interaction(ray, hit.t, hit.prim);
    return triangle(hit.prim).interaction(hit.triangle, hit.prim);
}

}  // namespace glint
