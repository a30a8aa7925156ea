// Spatial splits (Stich, Friedrich and Dietrich, "Spatial splits in bounding volume hierarchies",
// HPG 2009), a policy of the SAH builder (core/accel/sah_builder_impl.h): a node may also be
// split by a plane that cuts its triangles, each cut one becoming a reference on both sides with
// the box of its part there, where that lowers the SAH cost. Long or oblique triangles then stop filling their
// boxes' overlapping neighbours. Only the benchmarks build such trees (bvh_vs_embree, ray_loop):
// the renderer and `glint trace-rays` use the binned tree, which builds faster, until a
// measurement shows the split tree pays for the renders glint makes.
#pragma once

#include <span>
#include <vector>

#include "accel/sah_builder_impl.h"
#include "scene/geometry.h"
#include "shapes/triangle.h"

namespace glint {

class SpatialSplits {
public:
    // A step cost of 1, which splits nearly every node down to one triangle, and lets the
    // collapse choose the leaves (bvh_collapse.h).
    static constexpr float kTraversalCost = 1.0f;

    // Primitive i is triangles[i], which must outlive the policy: the triangles as the
    // Geometry stores them (as SplitGeometry gives them), so that the parts bound what it tests.
    explicit SpatialSplits(std::span<const Triangle> triangles, double budget = 0.3)
        : triangles_(triangles), budget_(budget) {}

    double budget() const { return budget_; }
    float overlap_share() const;
    float best_plane(std::span<const Bounds3> boxes, std::span<const uint32_t> prims, const Bounds3& node,
                     SplitPlane& plane) const;
    Bounds3 part(uint32_t prim, const Bounds3& box) const;

private:
    std::span<const Triangle> triangles_;
    double budget_;  // at most this many references more per primitive
};
static_assert(SplitsByPlanes<SpatialSplits>);

// In a tree split by planes a triangle may lie in several leaves, so a leaf's test leaves a ray's
// own triangle out by its index (geometry_queries.h): a load and a compare more per leaf than
// the renderer's table on the position.
struct LeaveOutByIndex {
    static uint32_t key(const Geometry& geometry, uint32_t prim) { return geometry.triangle_index(prim); }
    static unsigned lanes(const Geometry& geometry, uint32_t key, uint32_t first);
};

// glint's triangles with the tree with spatial splits, asked as a Geometry is.
class SplitGeometry {
public:
    SplitGeometry() = default;
    explicit SplitGeometry(const std::vector<Triangle>& triangles);

    bool intersect(const Ray& ray, uint32_t self, Hit& hit) const;
    bool occluded(const Ray& ray, uint32_t self, uint32_t target = kNoPrimitive) const;
    const Bvh& triangle_bvh() const { return geometry_.triangle_bvh(); }
    size_t memory_bytes() const { return geometry_.memory_bytes(); }
    void set_isa(Isa isa) { geometry_.set_isa(isa); }

private:
    Geometry geometry_;
};

// A box around the part of triangle t inside `box` (empty if none): never smaller than that
// part, and at most a few float units wider.
Bounds3 clipped_bounds(const Triangle& t, const Bounds3& box);
// A box around the part of triangle t in the slab lower <= x[axis] <= upper: the vertices
// inside it and the points where the edges cross its planes. Cheaper than clipped_bounds (no
// polygon), and exact but for the crossings' rounding, which may leave a part a few units in
// the last place outside it: for estimates, such as the spatial splits' costs.
Bounds3 slab_bounds(const Triangle& t, int axis, double lower, double upper);

}  // namespace glint
