// The binary tree that binned SAH builds over primitive boxes (Wald, "On fast construction of
// SAH-based bounding volume hierarchies", 2007). Bvh collapses it to sixteen-wide nodes
// (bvh_collapse.h).
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "base/bounds.h"
#include "shapes/triangle.h"

namespace glint {

struct BinaryNode {
    FloatBox box;
    uint32_t first;  // leaf: first position in build order; inner node: left child (right = first + 1)
    uint32_t count;  // leaf: number of primitives (> 0); inner node: 0
    bool is_leaf() const { return count != 0; }
    double half_area() const {
        const double x = double(box.hi[0]) - box.lo[0], y = double(box.hi[1]) - box.lo[1], z = double(box.hi[2]) - box.lo[2];
        return x * y + y * z + z * x;
    }
};

struct BinaryTree {
    static constexpr int kMaxDepth = 128;   // SAH below depth 64, median splits beyond
    static constexpr uint32_t kMaxLeafSize = 4;

    std::vector<BinaryNode> nodes;  // root first; empty when no primitive has a box
    std::vector<uint32_t> order;    // build order: position -> primitive, the tree's primitives only
};

// Spatial splits (Stich, Friedrich and Dietrich, "Spatial splits in bounding volume hierarchies",
// HPG 2009): a node may also be split by a plane that cuts its triangles, each cut one becoming a
// reference on both sides with the box of its part there, where that lowers the SAH cost. Long
// or oblique triangles then stop filling their boxes' overlapping neighbours. The tree's order
// may name a triangle several times.
struct SpatialSplits {
    std::span<const Triangle> triangles;  // primitive i is triangles[i]
    double budget = 0.3;                  // at most this many references more per primitive
};

// Primitives with empty boxes are left out. `splits`, if given, allows spatial splits.
BinaryTree build_sah_tree(std::span<const Bounds3> prim_bounds, const SpatialSplits* splits = nullptr);

}  // namespace glint
