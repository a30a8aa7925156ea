// The renderer's instances of the queries (geometry_queries.h), with the sphere and cut-out
// tests they call, in one unit so that those calls may be inlined.
#include "scene/geometry_queries.h"

namespace glint {

// The renderer's queries; the benchmarks instantiate their own for trees split by planes.
template bool Geometry::intersect<LeaveOutByPosition>(const Ray& ray, uint32_t self, Hit& hit) const;
template bool Geometry::occluded<LeaveOutByPosition>(const Ray& ray, uint32_t self, uint32_t target) const;

bool Geometry::closest_sphere(Ray& ray, uint32_t self, Hit& hit) const {
    if (accelerator_ != Accelerator::bvh) {
        double t;
        const int prim = sphere_list_.closest(ray, self, t);
        if (prim < 0) return false;
        hit = {t, static_cast<uint32_t>(prim), {}};
        ray.tmax = t;
        return true;
    }
    auto test = [&](uint32_t prim, Ray& r) {
        double t;
        if (!spheres_[prim].intersect(r, prim == self, t)) return false;
        hit = {t, prim, {}};
        r.tmax = t;
        return true;
    };
    return sphere_bvh_.closest(ray, [&](uint32_t first, uint32_t count, Ray& r) {
        bool found = false;
        for (uint32_t pos = first; pos < first + count; ++pos) found |= test(sphere_bvh_.order()[pos], r);
        return found;
    });
}

bool Geometry::sphere_blocks(const Ray& ray, uint32_t self, uint32_t target) const {
    if (accelerator_ != Accelerator::bvh) return sphere_list_.any(ray, self, target);
    return sphere_bvh_.any(ray, [&](uint32_t first, uint32_t count, const Ray& r) {
        for (uint32_t pos = first; pos < first + count; ++pos) {
            const uint32_t prim = sphere_bvh_.order()[pos];
            double t;
            if (prim != target && spheres_[prim].intersect(r, prim == self, t)) return true;
        }
        return false;
    });
}

bool Geometry::cut_away(const Hit& hit) const {
    const uint32_t index = triangle_index(hit.prim);
    const uint32_t mask = cutouts_.mask_of_triangle[index];
    if (mask == CutOuts::kNoMask) return false;
    const Uv uv = attributes_.uvs.empty() ? Uv{} : attributes_.uvs[index].at(hit.triangle.b1, hit.triangle.b2);
    return !cutouts_.masks[mask].keeps(uv);
}

}  // namespace glint
