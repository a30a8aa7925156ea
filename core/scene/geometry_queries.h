// Geometry's ray queries, written once over how a leaf's test leaves out the ray's own triangle
// (and a shadow ray's target). geometry_queries.cpp instantiates them for the renderer's trees, where
// each triangle has one position; the benchmarks' trees split by planes (a triangle in several
// leaves) bring their own way (bench/spatial_splits.h). A way is a type with
//   static uint32_t key(const Geometry&, uint32_t prim): what to look for (kNoPrimitive's key
//     must leave out nothing), and
//   static unsigned lanes(const Geometry&, uint32_t key, uint32_t first): the lanes of the run
//     at position `first` that hold that triangle.
#pragma once

#include <algorithm>

#include "scene/geometry.h"

namespace glint {

// By table on the position: 0 from four lanes on (kNoPrimitive and positions before `first`
// included). A lane past the end of a shorter run names no triangle of it, and the run test
// looks only at the run's own lanes.
struct LeaveOutByPosition {
    static uint32_t key(const Geometry& geometry, uint32_t prim) { return geometry.position(prim); }
    static unsigned lanes(const Geometry&, uint32_t key, uint32_t first) {
        static constexpr unsigned kLane[triangle_run::kMaxSize + 1] = {0b1, 0b10, 0b100, 0b1000, 0};
        return kLane[std::min(key - first, triangle_run::kMaxSize)];
    }
};

// A triangle is flat, so a ray leaving it cannot meet it again; a sphere is told, so that it
// keeps only the far root (see Sphere::intersect).
template <typename LeaveOut, bool kAvx512>
inline bool Geometry::closest_triangle(Ray& ray, uint32_t self, Hit& hit) const {
    const uint32_t skip = LeaveOut::key(*this, self);
    const RayShear shear(ray);
    const RunTest run_test(shear);
    auto test_run = [&](uint32_t first, uint32_t count, Ray& r) __attribute__((always_inline)) {
        const unsigned left_out = LeaveOut::lanes(*this, skip, first);
        const int i = run_test.closest(&triangle_runs_[9 * size_t(first)], count, left_out, r, hit.triangle);
        if (i < 0) return false;
        const uint32_t pos = first + static_cast<uint32_t>(i);
        hit.t = r.tmax = hit.triangle.t;
        hit.prim = triangle_id(triangle_at_.empty() ? pos : triangle_at_[pos]);
        return true;
    };
    if (accelerator_ == Accelerator::bvh) return triangle_bvh_.closest<kAvx512>(ray, test_run);
    bool found = false;
    for (uint32_t pos = 0; pos < triangle_count_; ++pos) found |= test_run(pos, 1, ray);
    return found;
}

// The two instantiations of each triangle query. The target attribute lets GCC inline the
// AVX2 code (the traversal, the box and run tests) into the AVX-512 function and allocate it
// there with 32 registers; nothing compiled for AVX-512 is emitted out of line where AVX2 code
// could link to it. Rounding is the same: the same IEEE operations, and -ffp-contract=off keeps
// AVX-512F's fused multiply-adds out; the one AVX-512 instruction of the closest-hit copy's own,
// the limit's rounding after a hit, rounds as the AVX code does (to_float_up_avx512). The leaf
// lambdas are always inlined: used by both copies, GCC would otherwise call them out of line,
// leaf test and all, from both.
template <typename LeaveOut>
bool Geometry::closest_triangle_avx2(Ray& ray, uint32_t self, Hit& hit) const {
    return closest_triangle<LeaveOut, false>(ray, self, hit);
}
template <typename LeaveOut>
bool Geometry::closest_triangle_avx512(Ray& ray, uint32_t self, Hit& hit) const {
    return closest_triangle<LeaveOut, true>(ray, self, hit);
}
template <typename LeaveOut>
bool Geometry::triangle_blocks_avx2(const Ray& ray, uint32_t self, uint32_t target) const {
    return triangle_blocks<LeaveOut>(ray, self, target);
}
template <typename LeaveOut>
bool Geometry::triangle_blocks_avx512(const Ray& ray, uint32_t self, uint32_t target) const {
    return triangle_blocks<LeaveOut>(ray, self, target);
}

template <typename LeaveOut>
bool Geometry::closest_triangle_hit(Ray& ray, uint32_t self, Hit& hit) const {
    return isa_ == Isa::avx512 ? closest_triangle_avx512<LeaveOut>(ray, self, hit)
                               : closest_triangle_avx2<LeaveOut>(ray, self, hit);
}

// Each hit in a hole moves the ray's start to it, and the search goes on behind.
// The ray's own tmin is kept: the spheres are tested on it next.
template <typename LeaveOut>
bool Geometry::closest_past_cutouts(Ray& ray, uint32_t self, Hit& hit) const {
    Ray r = ray;
    while (closest_triangle_hit<LeaveOut>(r, self, hit)) {
        if (!cut_away(hit)) {
            ray.tmax = r.tmax;
            return true;
        }
        r.tmin = hit.t;
        r.tmax = ray.tmax;
    }
    return false;
}

template <typename LeaveOut>
bool Geometry::blocked_past_cutouts(const Ray& ray, uint32_t self, uint32_t target) const {
    Ray r = ray;
    Hit hit;
    while (closest_triangle_hit<LeaveOut>(r, self, hit)) {
        if (hit.prim != target && !cut_away(hit)) return true;
        r.tmin = hit.t;
        r.tmax = ray.tmax;
    }
    return false;
}

template <typename LeaveOut>
bool Geometry::intersect(const Ray& ray, uint32_t self, Hit& hit) const {
    if (!has_finite_origin_and_direction(ray)) return false;  // would visit every node for nothing
    Ray r = ray;
    // A mesh scene pays nothing for spheres, not even the call, and a sphere scene nothing for
    // triangles (not even the ray's shear).
    const bool triangle_hit = !run_slot_.empty() && (has_cutouts() ? closest_past_cutouts<LeaveOut>(r, self, hit)
                                                                   : closest_triangle_hit<LeaveOut>(r, self, hit));
    return (!spheres_.empty() && closest_sphere(r, self, hit)) || triangle_hit;
}

template <typename LeaveOut>
inline bool Geometry::triangle_blocks(const Ray& ray, uint32_t self, uint32_t target) const {
    const uint32_t skip = LeaveOut::key(*this, self), wanted = LeaveOut::key(*this, target);
    const RayShear shear(ray);
    const RunTest run_test(shear);
    auto blocks = [&](uint32_t first, uint32_t count, const Ray& r) __attribute__((always_inline)) {
        const unsigned left_out = LeaveOut::lanes(*this, skip, first) | LeaveOut::lanes(*this, wanted, first);
        return run_test.any(&triangle_runs_[9 * size_t(first)], count, left_out, r);
    };
    if (accelerator_ == Accelerator::bvh) return triangle_bvh_.any(ray, blocks);
    for (uint32_t pos = 0; pos < triangle_count_; ++pos)
        if (blocks(pos, 1, ray)) return true;
    return false;
}

template <typename LeaveOut>
bool Geometry::occluded(const Ray& ray, uint32_t self, uint32_t target) const {
    if (!has_finite_origin_and_direction(ray)) return false;
    return (!spheres_.empty() && sphere_blocks(ray, self, target)) ||
           (!run_slot_.empty() && (has_cutouts() ? blocked_past_cutouts<LeaveOut>(ray, self, target)
                                   : isa_ == Isa::avx512 ? triangle_blocks_avx512<LeaveOut>(ray, self, target)
                                                         : triangle_blocks_avx2<LeaveOut>(ray, self, target)));
}

}  // namespace glint
