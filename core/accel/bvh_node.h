// The node of the sixteen-wide Bvh and the word that says where each of its children leads: the
// layout the traversal (bvh.h) reads and the collapse (bvh_collapse.h) writes, in a header of its
// own so that both include it and neither includes the other.
#pragma once

#include <cstdint>

#include "accel/ray_box_test.h"
#include "accel/sah_builder.h"

namespace glint {

// Where a child slot leads, in one word. A leaf: its first position in build order, shifted
// left by three, and its primitive count (1..kMaxLeafSize) in the low three bits. An inner node:
// its offset in the node array in 8-byte units (a multiple of eight, so the low bits are 0),
// which the traversal turns into an address with one scaled add. One word per child keeps a
// node at 448 bytes and lets the traversal stack hold a child and its entry distance in one
// 64-bit key.
struct ChildRef {
    static constexpr uint32_t kCountBits = 3;
    static constexpr uint32_t kNodeUnits = 56;  // sizeof(BvhNode) / 8
    // Keeps every offset in 32 bits: a tree has fewer nodes than primitives.
    static constexpr uint32_t kMaxPrimitives = uint32_t{1} << 26;
    static constexpr uint32_t node(uint32_t index) { return index * kNodeUnits; }
    static constexpr uint32_t leaf(uint32_t first, uint32_t count) { return first << kCountBits | count; }
    static constexpr uint32_t node_index(uint32_t ref) { return ref / kNodeUnits; }
    static constexpr uint32_t first(uint32_t ref) { return ref >> kCountBits; }
    static constexpr uint32_t count(uint32_t ref) { return ref & ((1u << kCountBits) - 1); }
};
static_assert(BinaryTree::kMaxLeafSize < (1u << ChildRef::kCountBits));
static_assert(uint64_t{ChildRef::kMaxPrimitives} * ChildRef::kNodeUnits < (uint64_t{1} << 32));

// Children a node holds: two box tests' worth. Wider nodes mean fewer node visits a ray (by the
// SAH's estimate), and a visit's two box tests are independent, so a visit waits for its memory
// about as long as one of eight children; the price is 448-byte nodes, seven cache lines.
inline constexpr int kBvhWidth = 2 * kBoxLanes;

// 448 bytes, seven cache lines: the boxes of up to sixteen children and where each child leads.
// Slot s's box is lane s % 8 of boxes[s / 8].
struct alignas(64) BvhNode {
    WideBox boxes[kBvhWidth / kBoxLanes];
    uint32_t child[kBvhWidth];  // ChildRef words; an unused slot holds 0 behind an empty box

    float& plane(int p, int slot) { return boxes[slot / kBoxLanes].planes[p][slot % kBoxLanes]; }
    float plane(int p, int slot) const { return boxes[slot / kBoxLanes].planes[p][slot % kBoxLanes]; }
    bool used(int slot) const { return boxes[slot / kBoxLanes].used(slot % kBoxLanes); }
    double half_area(int slot) const { return boxes[slot / kBoxLanes].half_area(slot % kBoxLanes); }
};
static_assert(sizeof(BvhNode) == 8 * ChildRef::kNodeUnits);

}  // namespace glint
