// An eight-wide bounding volume hierarchy over any primitives given by their boxes. Built as a
// binary tree by binned SAH (sah_builder.h) and collapsed to eight children per node (bvh.cpp);
// traversed iteratively, nearest child first, testing a node's eight child boxes at once in AVX
// (ray_box_test.h). Primitives are addressed by their position in build order, so a caller can
// store its primitives in that order and read a leaf's primitives as one contiguous run; the
// primitive tests are template parameters, so the hot loop makes no virtual or indirect calls.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "bounds.h"
#include "ray_box_test.h"
#include "sah_builder.h"

namespace glint {

// 256 bytes, four cache lines: the boxes of up to eight children and where each child leads.
struct alignas(64) BvhNode {
    WideBox boxes;
    uint32_t child[kBvhWidth];  // inner child: node index; leaf: its first position in build order
    uint32_t count[kBvhWidth];  // leaf: number of primitives (> 0); inner child or unused slot: 0
};
static_assert(sizeof(BvhNode) == 256);

class Bvh {
public:
    static constexpr int kMaxDepth = BinaryTree::kMaxDepth;  // a wide tree is no deeper

    Bvh() = default;
    // Builds over primitives 0..n-1; primitives with empty boxes are left out of the tree.
    static Bvh build(std::span<const Bounds3> prim_bounds);

    // Build order: position -> primitive. The primitives in the tree come first (the leaves
    // cover positions 0..tree_size()-1), those left out follow.
    const std::vector<uint32_t>& order() const { return order_; }
    uint32_t tree_size() const { return tree_size_; }
    const std::vector<BvhNode>& nodes() const { return nodes_; }
    size_t memory_bytes() const { return nodes_.size() * sizeof(BvhNode); }

    // Closest hit. `test(position, ray)` intersects the primitive at that build-order position
    // and, on a hit, shrinks ray.tmax to it and returns true. Returns whether anything was hit.
    template <typename Test>
    bool closest(Ray& ray, Test&& test) const {
        if (nodes_.empty()) return false;
        const RayBoxTest box(ray);
        Pending stack[kStackSize];
        int size = 0;
        Pending current{0, 0, 0};
        float tmax = to_float_up(ray.tmax);
        bool found = false;
        for (;;) {
            if (current.count == 0) {
                const BvhNode& node = nodes_[current.index];
                __m256 entries;
                const int mask = box.hit(node.boxes, tmax, entries);
                if (mask != 0 && (mask & (mask - 1)) == 0) {  // one child entered: no stack needed
                    const int c = __builtin_ctz(static_cast<unsigned>(mask));
                    current = {node.child[c], node.count[c], 0};
                    continue;
                }
                size = push_children(node, mask, entries, stack, size);
            } else {
                bool leaf_hit = false;
                for (uint32_t i = current.index; i < current.index + current.count; ++i) leaf_hit |= test(i, ray);
                if (leaf_hit) {  // only a hit moves the limit; rounding it costs more than the test's share
                    found = true;
                    tmax = to_float_up(ray.tmax);
                }
            }
            // The nearest pending subtree that can still hold something nearer than the best hit.
            do {
                if (size == 0) return found;
                current = stack[--size];
            } while (current.entry > tmax);
        }
    }

    // Any hit in (tmin, tmax]: `test(position, ray)` returns whether that primitive blocks the ray.
    template <typename Test>
    bool any(const Ray& ray, Test&& test) const {
        if (nodes_.empty()) return false;
        const RayBoxTest box(ray);
        const float tmax = to_float_up(ray.tmax);
        Pending stack[kStackSize];
        int size = 0;
        Pending current{0, 0, 0};
        for (;;) {
            if (current.count == 0) {
                __m256 entry;
                const BvhNode& node = nodes_[current.index];
                for (int mask = box.hit(node.boxes, tmax, entry); mask != 0; mask &= mask - 1) {
                    const int c = __builtin_ctz(static_cast<unsigned>(mask));
                    stack[size++] = {node.child[c], node.count[c], 0};
                }
            } else {
                for (uint32_t i = current.index; i < current.index + current.count; ++i)
                    if (test(i, ray)) return true;
            }
            if (size == 0) return false;
            current = stack[--size];
        }
    }

private:
    // A subtree waiting on the traversal stack: a node (count 0) or a leaf's run of positions.
    struct Pending {
        uint32_t index;
        uint32_t count;
        float entry;
    };
    static constexpr int kStackSize = (kBvhWidth - 1) * kMaxDepth + 1;  // each level leaves at most 7 behind

    // Pushes the children in `mask`, farthest first, so the nearest is popped next. Returns the
    // new stack size.
    static int push_children(const BvhNode& node, int mask, __m256 entries, Pending* stack, int size) {
        alignas(32) float entry[kBvhWidth];
        _mm256_store_ps(entry, entries);
        const int first = size;
        for (; mask != 0; mask &= mask - 1) {
            const int c = __builtin_ctz(static_cast<unsigned>(mask));
            // Insertion into the run pushed from this node, kept sorted by decreasing entry.
            int at = size++;
            for (; at > first && stack[at - 1].entry < entry[c]; --at) stack[at] = stack[at - 1];
            stack[at] = {node.child[c], node.count[c], entry[c]};
        }
        return size;
    }

    std::vector<BvhNode> nodes_;
    std::vector<uint32_t> order_;
    uint32_t tree_size_ = 0;
};

}  // namespace glint
