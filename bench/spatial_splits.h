// Spatial splits (Stich, Friedrich and Dietrich, "Spatial splits in bounding volume hierarchies",
// HPG 2009) for the SAH builder's ReferenceSplitter hook: a node may also be split by a plane
// that cuts its triangles, each cut one becoming a reference on both sides with the box of its
// part there, where that lowers the SAH cost. Long or oblique triangles then stop filling their
// boxes' overlapping neighbours. Only the benchmarks build such trees (bvh_vs_embree, ray_loop):
// the renderer and `glint trace-rays` use the binned tree, which builds faster, until a
// measurement shows the split tree pays for the renders glint makes.
#pragma once

#include <span>
#include <vector>

#include "accel/sah_builder.h"
#include "shapes/triangle.h"

namespace glint {

class SpatialSplitter final : public ReferenceSplitter {
public:
    // Primitive i is triangles[i], which must outlive the splitter: the triangles as the
    // Geometry stores them (stored_triangles()), so that the parts bound what it tests.
    explicit SpatialSplitter(std::span<const Triangle> triangles, double budget = 0.3)
        : triangles_(triangles), budget_(budget) {}

    float traversal_cost() const override;
    double budget() const override { return budget_; }
    float overlap_share() const override;
    float best_plane(std::span<const Bounds3> boxes, std::span<const uint32_t> prims, const Bounds3& node,
                     SplitPlane& plane) const override;
    Bounds3 part(uint32_t prim, const Bounds3& box) const override;

private:
    std::span<const Triangle> triangles_;
    double budget_;  // at most this many references more per primitive
};

// The triangles as Geometry stores them: their vertices rounded to float (PackedTriangle).
std::vector<Triangle> stored_triangles(const std::vector<Triangle>& triangles);

// A box around the part of triangle t inside `box` (empty if none): never smaller than that
// part, and at most a few float units wider.
Bounds3 clipped_bounds(const Triangle& t, const Bounds3& box);
// A box around the part of triangle t in the slab lower <= x[axis] <= upper: the vertices
// inside it and the points where the edges cross its planes. Cheaper than clipped_bounds (no
// polygon), and exact but for the crossings' rounding, which may leave a part a few units in
// the last place outside it: for estimates, such as the spatial splits' costs.
Bounds3 slab_bounds(const Triangle& t, int axis, double lower, double upper);

}  // namespace glint
