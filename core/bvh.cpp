#include "bvh.h"

#include <algorithm>
#include <array>
#include <stdexcept>

namespace glint {
namespace {

// Collapses the binary tree to eight children per node: a node adopts the children of its
// largest-area inner child, again and again, while it has fewer than eight. The largest child is
// the one a ray most likely enters, so opening it saves the most box tests.
class Collapser {
public:
    explicit Collapser(const std::vector<BinaryNode>& binary) : binary_(binary) {}

    std::vector<BvhNode> run() {
        nodes_.reserve(binary_.size() / 2 + 1);
        nodes_.emplace_back();
        const BinaryNode& root = binary_[0];
        if (root.is_leaf())
            fill(0, 0, 1);
        else
            fill(0, root.first, 2);
        return std::move(nodes_);
    }

private:
    // Fills the node from binary nodes first and first + 1 (size 2), or from the root alone (size
    // 1). The two indices rather than an array by value: its copy made the call store eight bytes
    // and load sixteen, which the processor cannot forward.
    void fill(uint32_t node, uint32_t first, int size) {
        std::array<uint32_t, kBvhWidth> children{first, first + 1};
        while (size < kBvhWidth) {
            int widest = -1;
            for (int c = 0; c < size; ++c)
                if (!binary_[children[c]].is_leaf() &&
                    (widest < 0 || binary_[children[c]].half_area() > binary_[children[widest]].half_area()))
                    widest = c;
            if (widest < 0) break;
            const uint32_t left = binary_[children[widest]].first;
            children[widest] = left;
            children[size++] = left + 1;
        }
        order_for_any_hit(children, size);
        for (int slot = 0; slot < kBvhWidth; ++slot) set_slot(node, slot, slot < size ? &binary_[children[slot]] : nullptr);
        for (int slot = 0; slot < size; ++slot) {
            const BinaryNode& child = binary_[children[slot]];
            if (child.is_leaf()) continue;
            const auto index = static_cast<uint32_t>(nodes_.size());
            nodes_.emplace_back();
            nodes_[node].child[slot] = ChildRef::node(index);
            fill(index, child.first, 2);
        }
    }

    // The any-hit traversal visits a node's children in slot order and stops at the first hit,
    // so the likeliest to block a ray go first: leaves, which are tested at once, then the
    // largest boxes. The closest-hit traversal orders by distance and does not care. (Sponza's
    // diffuse any-hit queries 16% faster on the binned tree, 17% on the split one; the other
    // sets within noise: bench/BENCHMARKS.md, ninth round.)
    void order_for_any_hit(std::array<uint32_t, kBvhWidth>& children, int size) const {
        std::sort(children.begin(), children.begin() + size, [&](uint32_t a, uint32_t b) {
            const BinaryNode &x = binary_[a], &y = binary_[b];
            return x.is_leaf() != y.is_leaf() ? x.is_leaf() : x.half_area() > y.half_area();
        });
    }

    void set_slot(uint32_t node, int slot, const BinaryNode* child) {
        BvhNode& n = nodes_[node];
        constexpr float inf = std::numeric_limits<float>::infinity();
        for (int a = 0; a < 3; ++a) {
            n.boxes.planes[2 * a][slot] = child ? child->box.lo[a] : inf;
            n.boxes.planes[2 * a + 1][slot] = child ? child->box.hi[a] : -inf;
        }
        n.child[slot] = child && child->is_leaf() ? ChildRef::leaf(child->first, child->count) : 0;
    }

    const std::vector<BinaryNode>& binary_;
    std::vector<BvhNode> nodes_;
};

}  // namespace

Bvh Bvh::build(std::span<const Bounds3> prim_bounds, const SpatialSplits* splits) {
    const double references = double(prim_bounds.size()) * (1 + (splits ? splits->budget : 0));
    if (references > ChildRef::kMaxPrimitives) throw std::length_error("too many primitives for one BVH");
    BinaryTree tree = build_sah_tree(prim_bounds, splits);
    Bvh bvh;
    if (!tree.nodes.empty()) bvh.nodes_ = Collapser(tree.nodes).run();
    bvh.tree_size_ = static_cast<uint32_t>(tree.order.size());
    bvh.order_ = std::move(tree.order);
    bvh.order_.reserve(prim_bounds.size());
    for (uint32_t i = 0; i < prim_bounds.size(); ++i)
        if (prim_bounds[i].empty()) bvh.order_.push_back(i);
    return bvh;
}

}  // namespace glint
