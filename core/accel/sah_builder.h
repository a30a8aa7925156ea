// The binary tree that binned SAH builds over primitive boxes (Wald, "On fast construction of
// SAH-based bounding volume hierarchies", 2007). Bvh collapses it to sixteen-wide nodes
// (bvh_collapse.h).
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

// An axis plane: the axis and the coordinate there.
struct SplitPlane {
    int axis = -1;
    double position = 0;
};

// A second way to split a node, which a caller may give the builder: by an axis plane that cuts
// the references it crosses, each cut one becoming a reference on both sides with the box of
// its part there. The tree's order may then name a primitive several times. The builder leaves
// free slots for the references this adds, asks for a plane only where the children of the
// best split by centres overlap by more than overlap_share() of the root's half area, and takes
// the plane where it costs less. (The benchmarks' spatial splits are one: bench/spatial_splits.h.)
class ReferenceSplitter {
public:
    virtual ~ReferenceSplitter() = default;
    // One step down, relative to one primitive test, in the tree built with this splitter.
    virtual float traversal_cost() const = 0;
    // At most this many references more per primitive.
    virtual double budget() const = 0;
    virtual float overlap_share() const = 0;
    // The cheapest plane through a node of box `node` holding the references `boxes` (of the
    // primitives `prims`), and its unnormalised SAH cost (infinite if there is none).
    virtual float best_plane(std::span<const Bounds3> boxes, std::span<const uint32_t> prims, const Bounds3& node,
                             SplitPlane& plane) const = 0;
    // A box around the part of primitive `prim` inside `box` (empty if none).
    virtual Bounds3 part(uint32_t prim, const Bounds3& box) const = 0;
};

// How build_sah_tree uses the processor's cores; the defaults are the renderer's.
struct SahBuildConfig {
    // Inputs of at least this many primitives are built on several threads (without a
    // ReferenceSplitter): their top first, down to subtrees of at most an eighth of the
    // primitives, then the subtrees at once. The tree is the same as one thread's, numbered
    // otherwise: collapse_to_wide() makes the same wide tree of both.
    uint32_t parallel_from = 1 << 16;
    // Threads for those subtrees; 0: one per hardware thread.
    unsigned threads = 0;
};

// Primitives with empty boxes are left out. `splitter`, if given, may also split by planes.
BinaryTree build_sah_tree(std::span<const Bounds3> prim_bounds, const ReferenceSplitter* splitter = nullptr,
                          const SahBuildConfig& config = {});

}  // namespace glint
