#include "accel/bvh_collapse.h"

#include <immintrin.h>

#include <algorithm>
#include <array>
#include <limits>
#include <memory>
#include <utility>

namespace glint {
namespace {

// The dynamic programme of collapse_to_wide(): a plan for every binary node, then the wide
// nodes and leaves it picks, depth first.
class Collapser {
public:
    explicit Collapser(const std::vector<BinaryNode>& binary)
        : binary_(binary), plans_(std::make_unique_for_overwrite<Plan[]>(binary.size())) {}

    std::vector<BvhNode> run() {
        plan();
        nodes_.reserve(binary_.size() / 2 + 1);
        nodes_.emplace_back();
        std::array<uint32_t, kBvhWidth> children{};
        int size = 0;
        if (binary_[0].is_leaf())
            children[size++] = 0;
        else
            gather_content(0, children, size);
        fill(0, children, size);
        return std::move(nodes_);
    }

private:
    // For a binary node and each number of slots i = 1..8, the least cost of its subtree when it
    // may fill at most i slots of its parent, and how: kOwnSlot puts the node in one slot (as a
    // leaf, or as a wide node of its own), k > 0 gives its left child k slots and its right one
    // the rest. Float areas, as the boxes are.
    static constexpr uint8_t kOwnSlot = 0;
    struct Plan {
        std::array<float, kBvhWidth> cost;
        std::array<uint8_t, kBvhWidth> left_slots;  // index i - 1
        uint8_t content_left;                       // as a wide node: the slots of its left child
        bool as_leaf;                               // in its own slot: a leaf, not a wide node
        uint32_t first, prims;                      // its subtree's run of build-order positions
    };

    // Children come after their parents in the binary tree, so one backward pass sees every
    // child before its parent. The choices are selects, not branches: which is cheaper is a
    // coin toss, and mispredicting it made this pass cost more than the greedy collapse.
    void plan() {
        for (size_t n = binary_.size(); n-- > 0;) {
            Plan& p = plans_[n];
            const BinaryNode& node = binary_[n];
            const auto area = static_cast<float>(node.half_area());
            const float leaf_cost = kLeafCost * area;
            if (node.is_leaf()) {
                p.cost.fill(leaf_cost);
                p.left_slots.fill(kOwnSlot);
                p.as_leaf = true;
                p.first = node.first;
                p.prims = node.count;
                continue;
            }
            const Plan &left = plans_[node.first], &right = plans_[node.first + 1];
            p.first = left.first;
            p.prims = left.prims + right.prims;
            std::array<float, kBvhWidth> split{};
            std::array<uint8_t, kBvhWidth> split_left{};
            share_slots(left, right, split, split_left);
            p.content_left = split_left[kBvhWidth - 1];
            const float node_cost = area + split[kBvhWidth - 1];
            // Any subtree of few enough primitives may be one leaf: they are one run.
            p.as_leaf = p.prims <= BinaryTree::kMaxLeafSize && leaf_cost < node_cost;
            p.cost[0] = p.as_leaf ? leaf_cost : node_cost;
            p.left_slots[0] = kOwnSlot;
            for (int i = 2; i <= kBvhWidth; ++i) {
                const bool own = p.cost[i - 2] <= split[i - 1];
                p.cost[i - 1] = own ? p.cost[i - 2] : split[i - 1];
                p.left_slots[i - 1] = own ? p.left_slots[i - 2] : split_left[i - 1];
            }
        }
    }

    // The least cost of two siblings sharing at most i slots, from i = 2 on, and the left one's
    // share: over k, the least of left.cost[k - 1] + right.cost[i - k - 1]. All i at once in
    // AVX, two registers of eight, one k after another: the right costs shifted up k lanes
    // behind +inf, which is never chosen, read unaligned from a copy padded with +inf: fewer
    // instructions than scalar loops over i and k, in a pass that runs once per binary node of
    // every build. Each choice starts from a valid one (k = 1), so that boxes
    // reaching infinity, whose costs are infinite or NaN, still give a tree; ties keep the lower k.
    // A subtree fills at most a slot a primitive, so its costs stop falling there: a k beyond the
    // left one's primitives, or an i beyond both's, chooses nothing new, and is not computed.
    static void share_slots(const Plan& left, const Plan& right, std::array<float, kBvhWidth>& cost,
                            std::array<uint8_t, kBvhWidth>& left_slots) {
        constexpr float inf = std::numeric_limits<float>::infinity();
        alignas(32) float padded[2 * kBvhWidth];
        std::fill(padded, padded + kBvhWidth, inf);
        std::copy(right.cost.begin(), right.cost.end(), padded + kBvhWidth);
        const auto sums = [&](int k, int half) {
            const __m256 shifted = _mm256_loadu_ps(padded + kBvhWidth - k + half * kBoxLanes);
            return _mm256_add_ps(_mm256_set1_ps(left.cost[k - 1]), shifted);
        };
        const int last_k = static_cast<int>(std::min<uint32_t>(kBvhWidth - 1, left.prims));
        // One half's lanes over k = 2 .. last: each half in registers of its own.
        const auto share = [&](int half, int last, __m256& best, __m256i& best_left) {
            best = sums(1, half);
            best_left = _mm256_set1_epi32(1);
            for (int k = 2; k <= last; ++k) {
                const __m256 c = sums(k, half);
                const __m256 better = _mm256_cmp_ps(c, best, _CMP_LT_OQ);
                best = _mm256_blendv_ps(best, c, better);
                best_left = _mm256_blendv_epi8(best_left, _mm256_set1_epi32(k), _mm256_castps_si256(better));
            }
        };
        __m256 best[2];
        __m256i best_left[2];
        // Lanes below k are +inf: from k = 8 on, only the upper half can change.
        share(0, std::min(last_k, kBoxLanes - 1), best[0], best_left[0]);
        if (left.prims + right.prims > kBoxLanes) {
            share(1, last_k, best[1], best_left[1]);
        } else {  // the upper half as the lower's last lane
            const __m256i last = _mm256_set1_epi32(kBoxLanes - 1);
            best[1] = _mm256_permutevar8x32_ps(best[0], last);
            best_left[1] = _mm256_permutevar8x32_epi32(best_left[0], last);
        }
        alignas(32) int32_t shares[kBvhWidth];
        for (int h = 0; h < 2; ++h) {
            _mm256_storeu_ps(cost.data() + h * kBoxLanes, best[h]);
            _mm256_store_si256(reinterpret_cast<__m256i*>(shares + h * kBoxLanes), best_left[h]);
        }
        for (int i = 0; i < kBvhWidth; ++i) left_slots[i] = static_cast<uint8_t>(shares[i]);
    }

    // The slots of binary node n's wide node.
    void gather_content(uint32_t n, std::array<uint32_t, kBvhWidth>& children, int& size) const {
        const uint8_t left = plans_[n].content_left;
        gather(binary_[n].first, left, children, size);
        gather(binary_[n].first + 1, kBvhWidth - left, children, size);
    }

    // Appends the slots that binary node n's subtree fills when it may take `slots` of them.
    void gather(uint32_t n, int slots, std::array<uint32_t, kBvhWidth>& children, int& size) const {
        const uint8_t left = plans_[n].left_slots[slots - 1];
        if (left == kOwnSlot) {
            children[size++] = n;
            return;
        }
        gather(binary_[n].first, left, children, size);
        gather(binary_[n].first + 1, slots - left, children, size);
    }

    void fill(uint32_t node, std::array<uint32_t, kBvhWidth>& children, int size) {
        order_for_any_hit(children, size);
        for (int slot = 0; slot < kBvhWidth; ++slot) set_slot(node, slot, slot < size ? children[slot] : kNone);
        for (int slot = 0; slot < size; ++slot) {
            if (plans_[children[slot]].as_leaf) continue;
            const auto index = static_cast<uint32_t>(nodes_.size());
            nodes_.emplace_back();
            nodes_[node].child[slot] = ChildRef::node(index);
            std::array<uint32_t, kBvhWidth> grandchildren{};
            int count = 0;
            gather_content(children[slot], grandchildren, count);
            fill(index, grandchildren, count);
        }
    }

    // The any-hit traversal visits a node's children in slot order and stops at the first hit,
    // so the likeliest to block a ray go first: leaves, which are tested at once, then the
    // largest boxes. The closest-hit traversal orders by distance and does not care. It pays
    // where rays are often blocked (diffuse shadow rays in a closed interior such as Sponza's)
    // and costs nothing elsewhere: the order is set once, at build time.
    void order_for_any_hit(std::array<uint32_t, kBvhWidth>& children, int size) const {
        // The keys computed once: the comparisons of std::sort recomputed the areas (and GCC 12
        // warns that its insertion sort might read past an array of eight).
        struct Key {
            bool leaf;
            float area;
            uint32_t child;
            bool goes_before(const Key& k) const { return leaf != k.leaf ? leaf : area > k.area; }
        };
        std::array<Key, kBvhWidth> keys;
        for (int i = 0; i < size; ++i)
            keys[i] = {plans_[children[i]].as_leaf, static_cast<float>(binary_[children[i]].half_area()), children[i]};
        for (int i = 1; i < size; ++i)
            for (int j = i; j > 0 && keys[j].goes_before(keys[j - 1]); --j) std::swap(keys[j], keys[j - 1]);
        for (int i = 0; i < size; ++i) children[i] = keys[i].child;
    }

    static constexpr uint32_t kNone = ~0u;
    void set_slot(uint32_t node, int slot, uint32_t child) {
        BvhNode& n = nodes_[node];
        constexpr float inf = std::numeric_limits<float>::infinity();
        const FloatBox* box = child != kNone ? &binary_[child].box : nullptr;
        for (int a = 0; a < 3; ++a) {
            n.plane(2 * a, slot) = box ? box->lo[a] : inf;
            n.plane(2 * a + 1, slot) = box ? box->hi[a] : -inf;
        }
        const Plan* p = child != kNone ? &plans_[child] : nullptr;
        n.child[slot] = p && p->as_leaf ? ChildRef::leaf(p->first, p->prims) : 0;
    }

    const std::vector<BinaryNode>& binary_;
    std::unique_ptr<Plan[]> plans_;
    std::vector<BvhNode> nodes_;
};

}  // namespace

std::vector<BvhNode> collapse_to_wide(const std::vector<BinaryNode>& binary) { return Collapser(binary).run(); }

}  // namespace glint
