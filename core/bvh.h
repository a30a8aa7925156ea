// A bounding volume hierarchy over any primitives given by their boxes: binned SAH build,
// 32-byte nodes in depth-first order with sibling pairs adjacent, and iterative traversal,
// nearest child first. The primitive tests are template parameters, so the hot loop makes no
// virtual or indirect calls.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "bounds.h"
#include "ray.h"

namespace glint {

struct BvhNode {
    FloatBox box;
    uint32_t first;  // leaf: first entry of Bvh::prims(); inner node: left child (right = first + 1)
    uint32_t count;  // leaf: number of primitives (> 0); inner node: 0
    bool is_leaf() const { return count != 0; }
};
static_assert(sizeof(BvhNode) == 32);

// Slab test of Williams et al. made robust as Ize ("Robust BVH ray traversal", JCGT 2013) does:
// far distances are scaled by 1 + 2·gamma(3) so that rounding never rejects a box the exact
// test would accept. A zero direction component gives an infinite inverse; a ray lying in a
// slab's plane then yields 0·inf = NaN, and the comparisons below are ordered so that a NaN
// never narrows the interval (the ray is inside that slab for every t).
class RayBoxTest {
public:
    explicit RayBoxTest(const Ray& ray) : o_(ray.o), inv_(1.0 / ray.d.x, 1.0 / ray.d.y, 1.0 / ray.d.z) {
        // The near plane of each slab is picked by the sign bit (so -0 counts as negative):
        // then a NaN can only come from a ray lying in a plane, never turn +inf into a near t.
        for (int a = 0; a < 3; ++a) negative_[a] = std::signbit(inv_[a]);
    }
    // Entry distance in `entry` when the box overlaps (tmin, tmax].
    bool hit(const FloatBox& box, double tmin, double tmax, double& entry) const {
        constexpr double pad = 1 + 2 * gamma(3);
        for (int a = 0; a < 3; ++a) {
            const double t_near = (double(negative_[a] ? box.hi[a] : box.lo[a]) - o_[a]) * inv_[a];
            const double t_far = (double(negative_[a] ? box.lo[a] : box.hi[a]) - o_[a]) * inv_[a] * pad;
            tmin = t_near > tmin ? t_near : tmin;  // false for NaN: the slab does not narrow
            tmax = t_far < tmax ? t_far : tmax;
        }
        entry = tmin;
        return tmin <= tmax;
    }

private:
    Vec3 o_, inv_;
    bool negative_[3];
};

class Bvh {
public:
    static constexpr int kMaxDepth = 128;

    Bvh() = default;
    // Builds over primitives 0..n-1; primitives with empty boxes are left out of the tree.
    static Bvh build(std::span<const Bounds3> prim_bounds);

    struct Output {
        std::vector<BvhNode> nodes;
        std::vector<uint32_t> prims;
    };

    const std::vector<BvhNode>& nodes() const { return nodes_; }
    const std::vector<uint32_t>& prims() const { return prims_; }
    size_t memory_bytes() const {
        return nodes_.size() * sizeof(BvhNode) + prims_.size() * sizeof(uint32_t);
    }

    // Closest hit. `test(prim, ray)` intersects one primitive and, on a hit, shrinks ray.tmax
    // to it and returns true. Returns whether anything was hit.
    template <typename Test>
    bool closest(Ray& ray, Test&& test) const {
        if (nodes_.empty()) return false;
        const RayBoxTest box(ray);
        double entry;
        if (!box.hit(nodes_[0].box, ray.tmin, ray.tmax, entry)) return false;
        struct Pending { uint32_t node; double entry; };
        Pending stack[kMaxDepth];
        int size = 0;
        uint32_t current = 0;
        bool found = false;
        for (;;) {
            const BvhNode& node = nodes_[current];
            if (node.is_leaf()) {
                for (uint32_t i = node.first; i < node.first + node.count; ++i)
                    found |= test(prims_[i], ray);
            } else {
                double el, er;
                const uint32_t l = node.first, r = node.first + 1;
                const bool hl = box.hit(nodes_[l].box, ray.tmin, ray.tmax, el);
                const bool hr = box.hit(nodes_[r].box, ray.tmin, ray.tmax, er);
                if (hl && hr) {
                    const bool left_first = el <= er;
                    stack[size++] = left_first ? Pending{r, er} : Pending{l, el};
                    current = left_first ? l : r;
                    continue;
                }
                if (hl || hr) {
                    current = hl ? l : r;
                    continue;
                }
            }
            // Pop the next subtree that can still hold something nearer than the best hit.
            do {
                if (size == 0) return found;
                --size;
            } while (stack[size].entry > ray.tmax);
            current = stack[size].node;
        }
    }

    // Any hit in (tmin, tmax]: `test(prim, ray)` returns whether that primitive blocks the ray.
    template <typename Test>
    bool any(const Ray& ray, Test&& test) const {
        if (nodes_.empty()) return false;
        const RayBoxTest box(ray);
        uint32_t stack[kMaxDepth];
        int size = 0;
        stack[size++] = 0;
        while (size > 0) {
            const BvhNode& node = nodes_[stack[--size]];
            double entry;
            if (!box.hit(node.box, ray.tmin, ray.tmax, entry)) continue;
            if (node.is_leaf()) {
                for (uint32_t i = node.first; i < node.first + node.count; ++i)
                    if (test(prims_[i], ray)) return true;
            } else {
                stack[size++] = node.first + 1;
                stack[size++] = node.first;
            }
        }
        return false;
    }

private:
    std::vector<BvhNode> nodes_;
    std::vector<uint32_t> prims_;
};

}  // namespace glint
