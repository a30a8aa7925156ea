#include "accel/bvh.h"

#include <stdexcept>

#include "accel/bvh_collapse.h"

namespace glint {

Bvh Bvh::build(std::span<const Bounds3> prim_bounds, const ReferenceSplitter* splitter) {
    const double references = double(prim_bounds.size()) * (1 + (splitter ? splitter->budget() : 0));
    if (references > ChildRef::kMaxPrimitives) throw std::length_error("too many primitives for one BVH");
    BinaryTree tree = build_sah_tree(prim_bounds, splitter);
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
