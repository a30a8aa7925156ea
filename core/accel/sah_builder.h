// The binary tree that binned SAH builds over primitive boxes (Wald, "On fast construction of
// SAH-based bounding volume hierarchies", 2007). Bvh collapses it to sixteen-wide nodes
// (bvh_collapse.h). The builder itself, a template a caller may compose variants of, is in
// sah_builder_impl.h.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "base/bounds.h"

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

// How build_sah_tree uses the processor's cores; the defaults are the renderer's.
struct SahBuildConfig {
    // Inputs of at least this many primitives are built on several threads (unless split by
    // planes, sah_builder_impl.h): their top first, down to subtrees of at most an eighth of the
    // primitives, then the subtrees at once. The tree is the same as one thread's, numbered
    // otherwise: collapse_to_wide() makes the same wide tree of both.
    uint32_t parallel_from = 1 << 16;
    // Threads for those subtrees; 0: one per hardware thread.
    unsigned threads = 0;
};

// Primitives with empty boxes are left out. The renderer's instance of the builder
// (sah_builder_impl.cpp).
BinaryTree build_sah_tree(std::span<const Bounds3> prim_bounds, const SahBuildConfig& config = {});

}  // namespace glint
