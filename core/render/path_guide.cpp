#include "render/path_guide.h"

#include <atomic>
#include <cmath>
#include <utility>

namespace glint {

PathGuide::PathGuide(const Bounds3& scene_bounds, const GuideConfig& config)
    : config_(config), bounds_(scene_bounds), nodes_(1), leaves_(1) {}

uint32_t PathGuide::leaf_at(const Vec3& p) const {
    uint32_t node = 0;
    while (nodes_[node].child != 0) node = nodes_[node].child + (p[nodes_[node].axis] >= nodes_[node].split);
    return nodes_[node].leaf;
}

void PathGuide::record(const Vec3& p, const Vec3& wi, double amount) {
    Leaf& leaf = leaves_[leaf_at(p)];
    std::atomic_ref<uint64_t>(leaf.records).fetch_add(1, std::memory_order_relaxed);
    leaf.directions.record(direction_to_square(wi), amount);
}

const GuideQuadtree* PathGuide::at(const Vec3& p) const {
    const GuideQuadtree& directions = leaves_[leaf_at(p)].directions;
    return directions.learned() ? &directions : nullptr;
}

void PathGuide::learn(uint64_t paths) {
    for (Leaf& leaf : leaves_)
        leaf.directions.learn_and_refine(config_.directional_threshold, config_.max_directional_depth);
    // The leaves as they stand, with their boxes, before any splits: in node order.
    std::vector<std::pair<uint32_t, Bounds3>> stack{{0, bounds_}}, to_split;
    while (!stack.empty()) {
        const auto [node, box] = stack.back();
        stack.pop_back();
        const Node& n = nodes_[node];
        if (n.child == 0) {
            to_split.push_back({node, box});
            continue;
        }
        Bounds3 low = box, high = box;
        low.hi[n.axis] = high.lo[n.axis] = n.split;
        stack.push_back({n.child + 1, high});
        stack.push_back({n.child, low});
    }
    const double threshold = config_.spatial_threshold * std::sqrt(double(paths) / 1e6);
    for (const auto& [node, box] : to_split) split(node, box, double(leaves_[nodes_[node].leaf].records), threshold);
    for (Leaf& leaf : leaves_) leaf.records = 0;
}

void PathGuide::split(uint32_t node, const Bounds3& box, double records, double threshold) {
    if (records <= threshold || leaves_.size() >= config_.max_leaves) return;
    const Vec3 extent = box.extent();
    const int axis = extent.x >= extent.y && extent.x >= extent.z ? 0 : extent.y >= extent.z ? 1 : 2;
    const uint32_t child = uint32_t(nodes_.size());
    const uint32_t leaf = nodes_[node].leaf;
    nodes_.push_back({0, 0, 0, leaf});
    nodes_.push_back({0, 0, 0, uint32_t(leaves_.size())});
    leaves_.push_back(leaves_[leaf]);
    Node& n = nodes_[node];
    n.child = child;
    n.axis = uint8_t(axis);
    n.split = box.centre()[axis];
    Bounds3 low = box, high = box;
    low.hi[axis] = high.lo[axis] = n.split;
    split(child, low, records / 2, threshold);
    split(child + 1, high, records / 2, threshold);
}

GuideStats PathGuide::stats() const {
    GuideStats s{nodes_.size(), leaves_.size(), 0, nodes_.size() * sizeof(Node) + leaves_.size() * sizeof(Leaf)};
    for (const Leaf& leaf : leaves_) {
        s.directional_nodes += leaf.directions.nodes();
        s.bytes += leaf.directions.bytes();
    }
    return s;
}

int guide_iterations(const GuideConfig& config, uint32_t job_spp) {
    int iterations = 0;
    while (iterations < config.max_iterations && double((uint64_t(2) << iterations) - 1) <= config.training_share * job_spp)
        ++iterations;
    return iterations;
}

}  // namespace glint
