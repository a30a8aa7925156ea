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

    Bvh::Output run() {
        nodes_.reserve(2 * prims_.size());
        nodes_.push_back({});
        build(0, 0, static_cast<uint32_t>(prims_.size()), 0);
        Bvh::Output out;
        out.nodes = std::move(nodes_);
        out.prims.reserve(prims_.size());
        for (const BuildPrim& p : prims_) out.prims.push_back(p.index);
        return out;
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
    if (prims.empty()) return bvh;
    Output out = Builder(std::move(prims)).run();
    bvh.nodes_ = std::move(out.nodes);
    bvh.prims_ = std::move(out.prims);
    return bvh;
}

}  // namespace glint
