// A sixteen-wide bounding volume hierarchy over any primitives given by their boxes. Built as a
// binary tree by binned SAH (sah_builder.h) and collapsed to nodes of up to sixteen children
// (bvh_collapse.h); traversed iteratively, nearest child first, testing a node's child boxes eight
// at a time in AVX (ray_box_test.h). Primitives are addressed by their position in build order, so a
// caller can store its primitives in that order and read a leaf's primitives as one contiguous run;
// the primitive tests are template parameters, so the hot loop makes no virtual or indirect calls.
#pragma once

#include <array>
#include <bit>
#include <cstdint>
#include <span>
#include <vector>

#include "base/bounds.h"
#include "accel/bvh_node.h"
#include "accel/sah_builder.h"

namespace glint {

class Bvh {
public:
    static constexpr int kMaxDepth = BinaryTree::kMaxDepth;  // a wide tree is no deeper

    Bvh() = default;
    // Builds over primitives 0..n-1; primitives with empty boxes are left out of the tree.
    // Throws std::length_error beyond ChildRef::kMaxPrimitives primitives.
    static Bvh build(std::span<const Bounds3> prim_bounds);
    // The tree `tree`, built over `prim_bounds` by another policy of the SAH builder
    // (sah_builder_impl.h), such as the benchmarks' spatial splits, whose leaves may hold a
    // primitive in several places. Throws std::length_error beyond ChildRef::kMaxPrimitives
    // references.
    static Bvh from_tree(BinaryTree tree, std::span<const Bounds3> prim_bounds);

    // Build order: position -> primitive. The tree's references come first (the leaves cover
    // positions 0..tree_size()-1; in a tree split by planes a primitive may appear more than
    // once), the primitives left out follow.
    const std::vector<uint32_t>& order() const { return order_; }
    uint32_t tree_size() const { return tree_size_; }
    const std::vector<BvhNode>& nodes() const { return nodes_; }
    size_t memory_bytes() const { return nodes_.size() * sizeof(BvhNode); }

    // The leaves as runs of build-order positions: f(first, count) for each.
    template <typename F>
    void for_each_leaf(F&& f) const {
        for (const BvhNode& node : nodes_)
            for (uint32_t ref : node.child)
                if (ChildRef::count(ref) > 0) f(ChildRef::first(ref), ChildRef::count(ref));
    }

    // Closest hit. `test(first, count, ray)` intersects the leaf's primitives at build-order
    // positions first..first+count-1, in that order, shrinking ray.tmax to each hit, and returns
    // whether any was hit. Returns whether anything was hit.
    // Always inlined, as is any(): a call's prologue, spills and epilogue would be a sizeable
    // share of a short traversal, such as a primary ray's. kAvx512: the caller runs on AVX-512, whose embedded
    // rounding shortens the step from a hit to the next box test.
    template <bool kAvx512 = false, typename Test>
    [[gnu::always_inline]] bool closest(Ray& ray, Test&& test) const {
        if (nodes_.empty()) return false;
        // Nearly every ray takes the fused box test, so the branch is predicted.
        if (FusedRayBoxTest::covers(ray)) return closest<kAvx512>(ray, FusedRayBoxTest(ray), test);
        return closest_unfused<kAvx512>(ray, test);
    }

    // Any hit in (tmin, tmax]: `test(first, count, ray)` returns whether one of the leaf's
    // primitives blocks the ray.
    template <typename Test>
    [[gnu::always_inline]] bool any(const Ray& ray, Test&& test) const {
        if (nodes_.empty()) return false;
        if (FusedRayBoxTest::covers(ray)) return any(ray, FusedRayBoxTest(ray), test);
        return any_unfused(ray, test);
    }

private:
    // The traversals with RayBoxTest, for the rare rays FusedRayBoxTest does not cover, out of
    // line: inlined beside the fused one, they make the closest-hit function's code half again as
    // large and crowd the fused traversal, which nearly every ray takes, out of registers.
    template <bool kAvx512, typename Test>
    [[gnu::noinline]] bool closest_unfused(Ray& ray, Test& test) const {
        return closest<kAvx512>(ray, RayBoxTest(ray), test);
    }
    template <typename Test>
    [[gnu::noinline]] bool any_unfused(const Ray& ray, Test& test) const {
        return any(ray, RayBoxTest(ray), test);
    }

    // Each level leaves at most 15 behind, and the bottom holds kStackEnd.
    static constexpr int kStackSize = (kBvhWidth - 1) * kMaxDepth + 2;

    template <bool kAvx512, typename BoxTest, typename Test>
    [[gnu::always_inline]] bool closest(Ray& ray, const BoxTest& box, Test& test) const {
        const BvhNode* const nodes = nodes_.data();  // held here: the tests' stores might alias nodes_
        uint64_t stack[kStackSize];
        stack[0] = kStackEnd;  // entry distance 0: never culled
        uint64_t* top = stack + 1;
        uint32_t ref = ChildRef::node(0);
        float tmax = to_float_up(ray.tmax);
        __m256 tmax8 = _mm256_set1_ps(tmax);
        uint64_t cull = cull_key(tmax);
        bool found = false;
        for (;;) {
            if (ChildRef::count(ref) == 0) {
                const BvhNode& node = at(nodes, ref);
                __m256 entries[2];
                unsigned mask = hits(box, node, tmax8, entries);
                if (mask != 0) {
                    const unsigned first = first_slot(mask);
                    if (mask == 0) {  // one child entered: no stack
                        ref = node.child[first];
                        continue;
                    }
                    alignas(32) uint64_t keys[kBvhWidth];
                    store_keys(entries[0], node.child, keys);
                    store_keys(entries[1], node.child + kBoxLanes, keys + kBoxLanes);
                    uint64_t nearer = keys[first], farther = keys[first_slot(mask)];
                    order(nearer, farther);
                    if (mask == 0) {  // two: push the farther, enter the nearer
                        *top++ = farther;
                        ref = static_cast<uint32_t>(nearer);
                        continue;
                    }
                    top = push_sorted(keys, mask, nearer, farther, top);
                }
            } else {
                if (ref == kStackEnd) return found;
                if (test(ChildRef::first(ref), ChildRef::count(ref), ray)) {
                    // Only a hit moves the limit; rounding it costs more than the test's share.
                    found = true;
                    tmax = limit_after_hit<kAvx512>(ray.tmax);
                    tmax8 = _mm256_set1_ps(tmax);
                    cull = cull_key(tmax);
                }
            }
            // The nearest pending subtree that can still hold something nearer than the best hit.
            uint64_t next;
            do next = *--top;
            while (next > cull);
            ref = static_cast<uint32_t>(next);
        }
    }

    template <typename BoxTest, typename Test>
    [[gnu::always_inline]] bool any(const Ray& ray, const BoxTest& box, Test& test) const {
        const BvhNode* const nodes = nodes_.data();
        const __m256 tmax = _mm256_set1_ps(to_float_up(ray.tmax));
        uint32_t stack[kStackSize + kBoxLanes];  // push_others stores eight words, whatever it pushes
        stack[0] = kStackEnd;
        uint32_t* top = stack + 1;
        uint32_t ref = ChildRef::node(0);
        for (;;) {
            if (ChildRef::count(ref) == 0) {
                __m256 entries[2];
                const BvhNode& node = at(nodes, ref);
                unsigned mask = hits(box, node, tmax, entries);
                if (mask != 0) {
                    ref = node.child[first_slot(mask)];
                    top = push_others(node.child, mask & kHalfMask, top);
                    top = push_others(node.child + kBoxLanes, mask >> kBoxLanes, top);
                    continue;
                }
            } else {
                if (ref == kStackEnd) return false;
                if (test(ChildRef::first(ref), ChildRef::count(ref), ray)) return true;
            }
            ref = *--top;
        }
    }

    // The bottom of the traversal stack, so that popping needs no emptiness test: a ChildRef
    // that reads as a leaf, which the leaf branch checks for (2.3 leaf visits a Sponza diffuse
    // ray against 7.7 pops on the eight-wide tree), but that no real leaf can be, as its first
    // position is out of range.
    static constexpr uint32_t kStackEnd = ~0u;
    static_assert(ChildRef::first(kStackEnd) >= ChildRef::kMaxPrimitives && ChildRef::count(kStackEnd) != 0);

    // The node's sixteen boxes, tested as two independent eight: bit s of the result for slot s.
    template <typename BoxTest>
    [[gnu::always_inline]] static unsigned hits(const BoxTest& box, const BvhNode& node, __m256 tmax,
                                                __m256 entries[2]) {
        const auto low = static_cast<unsigned>(box.hit(node.boxes[0], tmax, entries[0]));
        const auto high = static_cast<unsigned>(box.hit(node.boxes[1], tmax, entries[1]));
        return low | high << kBoxLanes;
    }
    static constexpr unsigned kHalfMask = (1u << kBoxLanes) - 1;

    // For each mask of one box test's slots, its slots in ascending order, one byte each.
    static constexpr std::array<uint64_t, 1u << kBoxLanes> kSlotsOf = [] {
        std::array<uint64_t, 1u << kBoxLanes> slots{};
        for (unsigned mask = 0; mask < slots.size(); ++mask)
            for (unsigned slot = 0, n = 0; slot < kBoxLanes; ++slot)
                if (mask >> slot & 1) slots[mask] |= uint64_t{slot} << 8 * n++;
        return slots;
    }();

    static const BvhNode& at(const BvhNode* nodes, uint32_t ref) {
        return *reinterpret_cast<const BvhNode*>(reinterpret_cast<const char*>(nodes) + size_t{ref} * 8);
    }

    // A hit's distance rounded up to float. Without AVX-512, in AVX, without the branch of the
    // scalar rounding: whether the nearest float lies below the distance is a coin toss.
    template <bool kAvx512>
    static float limit_after_hit(double t) {
        if constexpr (kAvx512) return to_float_up_avx512(t);
        return _mm_cvtss_f32(to_float_up(_mm256_set1_pd(t)));
    }

    // The lowest slot in `mask`, which loses it.
    static unsigned first_slot(unsigned& mask) {
        const auto slot = static_cast<unsigned>(__builtin_ctz(mask));
        mask &= mask - 1;
        return slot;
    }

    // Each child as one sortable key, entry distance above and ChildRef below, in slot order.
    // An entry distance is kept as the bits of a non-negative float (the box tests give no
    // other), whose order as an unsigned integer is its order as a number. Built in AVX and read
    // back one load per key, against two loads, a shift and an or per key from the entry
    // distances stored alone.
    static void store_keys(__m256 entries, const uint32_t* children, uint64_t* keys) {
        const __m256i entry = _mm256_castps_si256(entries);
        const __m256i child = _mm256_load_si256(reinterpret_cast<const __m256i*>(children));
        // The unpacks interleave within 128-bit halves: with the 64-bit quarters first ordered
        // 0, 2, 1, 3, the low unpack yields the keys of slots 0-3 and the high one those of 4-7.
        const __m256i e = _mm256_permute4x64_epi64(entry, 0xD8), c = _mm256_permute4x64_epi64(child, 0xD8);
        _mm256_store_si256(reinterpret_cast<__m256i*>(keys), _mm256_unpacklo_epi32(c, e));
        _mm256_store_si256(reinterpret_cast<__m256i*>(keys + 4), _mm256_unpackhi_epi32(c, e));
    }
    // Keys above this belong to subtrees entered beyond tmax.
    static uint64_t cull_key(float tmax) {
        const uint32_t bits = tmax < 0 ? ~0u : std::bit_cast<uint32_t>(tmax);  // a negative limit culls nothing
        return uint64_t{bits} << 32 | 0xFFFFFFFFu;
    }

    // Pushes the children of eight slots that `mask` names (possibly none) in slot order, the
    // highest on top, with no branch on their number: VPERMD gathers them to the front of one
    // eight-word store.
    static uint32_t* push_others(const uint32_t* eight_children, unsigned mask, uint32_t* top) {
        const __m256i slots = _mm256_cvtepu8_epi32(_mm_loadl_epi64(reinterpret_cast<const __m128i*>(&kSlotsOf[mask])));
        const __m256i children = _mm256_load_si256(reinterpret_cast<const __m256i*>(eight_children));
        _mm256_storeu_si256(reinterpret_cast<__m256i*>(top), _mm256_permutevar8x32_epi32(children, slots));
        return top + std::popcount(mask);
    }

    // Two keys put in order by selects rather than a branch: which child is nearer is a coin toss.
    static void order(uint64_t& low, uint64_t& high) {
        const uint64_t a = low, b = high;
        low = b < a ? b : a;
        high = a ^ b ^ low;  // keys differ in their ChildRefs, so this is the other one
    }

    // Three or more children (one and two take cheaper paths of their own, in closest()):
    // pushes them all, sorted so that the nearest is on top, and returns the new top of the stack.
    static uint64_t* push_sorted(const uint64_t* keys, unsigned mask, uint64_t nearer, uint64_t farther,
                                 uint64_t* top) {
        // The third, most often the last, joins the sorted pair by selects: no mispredicted exit
        // from an insertion loop.
        uint64_t middle = keys[first_slot(mask)];
        order(middle, farther);
        order(nearer, middle);
        uint64_t* const first = top;
        top[0] = farther;
        top[1] = middle;
        top[2] = nearer;
        for (top += 3; mask != 0; ++top) {
            const uint64_t k = keys[first_slot(mask)];
            uint64_t* at = top;
            for (; at > first && at[-1] < k; --at) *at = at[-1];
            *at = k;
        }
        return top;
    }

    std::vector<BvhNode> nodes_;
    std::vector<uint32_t> order_;
    uint32_t tree_size_ = 0;
};

}  // namespace glint
