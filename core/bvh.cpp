#include "bvh.h"

#include <algorithm>
#include <array>

namespace glint {
namespace {

constexpr int kBins = 16;
constexpr uint32_t kMaxLeafSize = 4;
constexpr double kTraversalCost = 1.0;  // relative to one primitive test
// Below this depth SAH decides; deeper, splits fall back to the median so the tree's depth
// (and so the traversal stack) stays bounded whatever the input.
constexpr int kSahDepth = 64;

// The binary tree that SAH builds, before it is collapsed to four-wide nodes.
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

struct BuildPrim {
    Bounds3 bounds;
    Vec3 centre;
    uint32_t index;
};

struct Split {
    int axis = -1;
    double position = 0;
    double cost = kInfinity;
};

class Builder {
public:
    explicit Builder(std::vector<BuildPrim> prims) : prims_(std::move(prims)) {}

    // The binary tree, and the primitives in the order its leaves cover them.
    std::vector<BinaryNode> run(std::vector<uint32_t>& order) {
        nodes_.reserve(2 * prims_.size());
        nodes_.push_back({});
        build(0, 0, static_cast<uint32_t>(prims_.size()), 0);
        for (const BuildPrim& p : prims_) order.push_back(p.index);
        return std::move(nodes_);
    }

private:
    void build(uint32_t node, uint32_t begin, uint32_t end, int depth) {
        Bounds3 bounds, centres;
        for (uint32_t i = begin; i < end; ++i) {
            bounds.extend(prims_[i].bounds);
            centres.extend(prims_[i].centre);
        }
        nodes_[node].box = FloatBox::enclosing(bounds);
        const uint32_t count = end - begin;
        const Split split = depth < kSahDepth ? best_sah_split(begin, end, centres) : Split{};
        const double leaf_cost = count;
        const double split_cost = kTraversalCost + split.cost / bounds.half_area();
        if (count == 1 || (count <= kMaxLeafSize && leaf_cost <= split_cost)) {
            nodes_[node].first = begin;
            nodes_[node].count = count;
            return;
        }
        uint32_t mid = begin;
        if (split.axis >= 0) {
            const auto first_right = std::partition(
                prims_.begin() + begin, prims_.begin() + end,
                [&](const BuildPrim& p) { return p.centre[split.axis] < split.position; });
            mid = static_cast<uint32_t>(first_right - prims_.begin());
        }
        if (mid == begin || mid == end) mid = median_split(begin, end, centres);

        const auto left = static_cast<uint32_t>(nodes_.size());
        nodes_[node].first = left;
        nodes_[node].count = 0;
        nodes_.push_back({});
        nodes_.push_back({});
        build(left, begin, mid, depth + 1);
        build(left + 1, mid, end, depth + 1);
    }

    // Binned SAH (Wald 2007) over all three axes; cost is the unnormalised SAH sum.
    Split best_sah_split(uint32_t begin, uint32_t end, const Bounds3& centres) const {
        Split best;
        for (int axis = 0; axis < 3; ++axis) {
            const double lo = centres.lo[axis], extent = centres.hi[axis] - lo;
            if (!(extent > 0)) continue;
            std::array<Bounds3, kBins> bins;
            std::array<uint32_t, kBins> counts{};
            const double scale = kBins / extent;
            auto bin_of = [&](const BuildPrim& p) {
                return std::min(kBins - 1, static_cast<int>((p.centre[axis] - lo) * scale));
            };
            for (uint32_t i = begin; i < end; ++i) {
                const int b = bin_of(prims_[i]);
                bins[b].extend(prims_[i].bounds);
                ++counts[b];
            }
            // Sweep from the right to get each split's right-hand cost, then from the left.
            std::array<double, kBins> right_cost{};
            Bounds3 acc;
            uint32_t n = 0;
            for (int b = kBins - 1; b > 0; --b) {
                acc.extend(bins[b]);
                n += counts[b];
                right_cost[b] = acc.half_area() * n;
            }
            acc = Bounds3{};
            n = 0;
            for (int b = 0; b < kBins - 1; ++b) {
                acc.extend(bins[b]);
                n += counts[b];
                const double cost = acc.half_area() * n + right_cost[b + 1];
                if (n > 0 && n < end - begin && cost < best.cost)
                    best = {axis, lo + (b + 1) / scale, cost};
            }
        }
        return best;
    }

    uint32_t median_split(uint32_t begin, uint32_t end, const Bounds3& centres) {
        const int axis = max_axis(centres.extent());
        const uint32_t mid = begin + (end - begin) / 2;
        std::nth_element(prims_.begin() + begin, prims_.begin() + mid, prims_.begin() + end,
                         [axis](const BuildPrim& a, const BuildPrim& b) {
                             return a.centre[axis] < b.centre[axis];
                         });
        return mid;
    }

    std::vector<BuildPrim> prims_;
    std::vector<BinaryNode> nodes_;
};

// Collapses the binary tree to four children per node: a node adopts its children's children,
// largest surface area first, while it has fewer than four (Wald et al., "Getting rid of
// packets", 2008, and madmann91/bvh's mini-tree collapse follow the same greedy rule).
class Collapser {
public:
    explicit Collapser(const std::vector<BinaryNode>& binary) : binary_(binary) {}

    std::vector<BvhNode> run() {
        nodes_.reserve(binary_.size() / 2 + 1);
        nodes_.emplace_back();
        const BinaryNode& root = binary_[0];
        if (root.is_leaf())
            fill(0, {{0}}, 1);
        else
            fill(0, {{root.first, root.first + 1}}, 2);
        return std::move(nodes_);
    }

private:
    void fill(uint32_t node, std::array<uint32_t, 4> children, int size) {
        while (size < 4) {
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
        for (int slot = 0; slot < 4; ++slot) set_slot(node, slot, slot < size ? &binary_[children[slot]] : nullptr);
        for (int slot = 0; slot < size; ++slot) {
            const BinaryNode& child = binary_[children[slot]];
            if (child.is_leaf()) continue;
            const auto index = static_cast<uint32_t>(nodes_.size());
            nodes_.emplace_back();
            nodes_[node].child[slot] = index;
            fill(index, {{child.first, child.first + 1}}, 2);
        }
    }

    void set_slot(uint32_t node, int slot, const BinaryNode* child) {
        BvhNode& n = nodes_[node];
        constexpr float inf = std::numeric_limits<float>::infinity();
        for (int a = 0; a < 3; ++a) {
            n.boxes.planes[2 * a][slot] = child ? child->box.lo[a] : inf;
            n.boxes.planes[2 * a + 1][slot] = child ? child->box.hi[a] : -inf;
        }
        n.child[slot] = child && child->is_leaf() ? child->first : 0;
        n.count[slot] = child ? child->count : 0;
    }

    const std::vector<BinaryNode>& binary_;
    std::vector<BvhNode> nodes_;
};

}  // namespace

Bvh Bvh::build(std::span<const Bounds3> prim_bounds) {
    std::vector<BuildPrim> prims;
    prims.reserve(prim_bounds.size());
    for (uint32_t i = 0; i < prim_bounds.size(); ++i)
        if (!prim_bounds[i].empty())
            prims.push_back({prim_bounds[i], prim_bounds[i].centre(), i});
    Bvh bvh;
    bvh.tree_size_ = static_cast<uint32_t>(prims.size());
    bvh.order_.reserve(prim_bounds.size());
    if (!prims.empty()) bvh.nodes_ = Collapser(Builder(std::move(prims)).run(bvh.order_)).run();
    for (uint32_t i = 0; i < prim_bounds.size(); ++i)
        if (prim_bounds[i].empty()) bvh.order_.push_back(i);
    return bvh;
}

}  // namespace glint
