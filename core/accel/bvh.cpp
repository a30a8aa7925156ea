#include "accel/bvh.h"

#include <stdexcept>

#include "accel/bvh_collapse.h"

namespace glint {
namespace {

// Checked before a build, so that an input too large fails before the work.
void check_references(double references) {
    if (references > ChildRef::kMaxPrimitives) throw std::length_error("too many primitives for one BVH");
}

}  // namespace

Bvh Bvh::build(std::span<const Bounds3> prim_bounds) {
    check_references(double(prim_bounds.size()));
    return from_tree(build_sah_tree(prim_bounds), prim_bounds);
}

Bvh Bvh::from_tree(BinaryTree tree, std::span<const Bounds3> prim_bounds) {
    check_references(double(tree.order.size()));
    Bvh bvh;
    if (!tree.nodes.empty()) bvh.nodes_ = collapse_to_wide(tree.nodes);
    bvh.tree_size_ = static_cast<uint32_t>(tree.order.size());
    bvh.order_ = std::move(tree.order);
    bvh.order_.reserve(prim_bounds.size());
    for (uint32_t i = 0; i < prim_bounds.size(); ++i)
        if (prim_bounds[i].empty()) bvh.order_.push_back(i);
    return bvh;
}

}  // namespace glint
