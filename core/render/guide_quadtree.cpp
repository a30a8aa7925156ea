#include "render/guide_quadtree.h"

#include <algorithm>
#include <atomic>
#include <cmath>

namespace glint {
namespace {

constexpr double kBelowOne = 1 - 0x1p-53;

// u rescaled to [0, 1) within [lo, lo + width) of [0, 1).
double rescale(double u, double lo, double width) { return std::min((u - lo) / width, kBelowOne); }

double sum(const std::array<double, 4>& e) { return (e[0] + e[1]) + (e[2] + e[3]); }

}  // namespace

SquarePoint direction_to_square(const Vec3& d) {
    double phi = std::atan2(d.z, d.x);
    if (phi < 0) phi += 2 * kPi;
    return {std::clamp((1 + d.y) / 2, 0.0, kBelowOne), std::min(phi / (2 * kPi), kBelowOne)};
}

Vec3 square_to_direction(const SquarePoint& s) {
    const double cos_theta = 2 * s.x - 1, sin_theta = std::sqrt(std::max(0.0, 1 - cos_theta * cos_theta));
    const double phi = 2 * kPi * s.y;
    return {sin_theta * std::cos(phi), cos_theta, sin_theta * std::sin(phi)};
}

void ExactSum::add(uint64_t amount) {
    const uint64_t before = std::atomic_ref<uint64_t>(lo).fetch_add(amount, std::memory_order_relaxed);
    if (before + amount < before) std::atomic_ref<uint64_t>(hi).fetch_add(1, std::memory_order_relaxed);
}

double ExactSum::value() const { return std::ldexp(double(hi), 64 - GuideQuadtree::kFractionBits) +
                                        std::ldexp(double(lo), -GuideQuadtree::kFractionBits); }

GuideQuadtree::GuideQuadtree() : learned_(1), recording_(1) {}

int GuideQuadtree::quadrant(double& x, double& y) {
    const int qx = x >= 0.5, qy = y >= 0.5;
    x = std::min(2 * x - qx, kBelowOne);
    y = std::min(2 * y - qy, kBelowOne);
    return qx | qy << 1;
}

void GuideQuadtree::record(const SquarePoint& s, double amount) {
    const uint64_t fixed = uint64_t(std::ldexp(std::min(amount, kMaxAmount), kFractionBits));
    if (fixed == 0) return;
    double x = s.x, y = s.y;
    for (uint32_t node = 0;;) {
        const int q = quadrant(x, y);
        RecordingNode& n = recording_[node];
        n.energy[q].add(fixed);
        if (n.child[q] == 0) return;
        node = n.child[q];
    }
}

double GuideQuadtree::pdf(const SquarePoint& s) const {
    if (!learned()) return 0;
    double x = s.x, y = s.y, density = 1;
    for (uint32_t node = 0;;) {
        const int q = quadrant(x, y);
        const LearnedNode& n = learned_[node];
        density *= 4 * n.energy[q] / sum(n.energy);
        if (n.child[q] == 0 || density == 0) return density;
        node = n.child[q];
    }
}

SquarePoint GuideQuadtree::sample(double u1, double u2, double& pdf) const {
    double x0 = 0, y0 = 0, size = 1;
    u1 = std::min(u1, kBelowOne);
    u2 = std::min(u2, kBelowOne);
    pdf = 1;
    for (uint32_t node = 0;;) {
        const LearnedNode& n = learned_[node];
        const std::array<double, 4>& e = n.energy;
        const double total = sum(e), left = (e[0] + e[2]) / total;
        const int qx = u1 >= left;
        u1 = qx ? rescale(u1, left, 1 - left) : rescale(u1, 0, left);
        const double bottom = e[qx] / (e[qx] + e[qx + 2]);
        const int qy = u2 >= bottom;
        u2 = qy ? rescale(u2, bottom, 1 - bottom) : rescale(u2, 0, bottom);
        const int q = qx | qy << 1;
        pdf *= 4 * e[q] / total;
        size /= 2;
        x0 += qx * size;
        y0 += qy * size;
        if (n.child[q] == 0) return {std::min(x0 + size * u1, kBelowOne), std::min(y0 + size * u2, kBelowOne)};
        node = n.child[q];
    }
}

void GuideQuadtree::learn_and_refine(double threshold, int max_depth) {
    learned_.assign(recording_.size(), {});
    for (size_t i = 0; i < recording_.size(); ++i) {
        learned_[i].child = recording_[i].child;
        for (int q = 0; q < 4; ++q) learned_[i].energy[q] = recording_[i].energy[q].value();
    }
    total_ = sum(learned_[0].energy);
    refine(threshold, max_depth);
}

// Rebuilds the recording tree top-down from the learned energies; where the learned tree has no
// children, a quadrant's energy is taken as spread evenly over its four.
void GuideQuadtree::refine(double threshold, int max_depth) {
    struct Pending {
        uint32_t node;        // in the new tree
        int64_t learned;      // the learned node over the same square, or -1
        std::array<double, 4> energy;
        int depth;
    };
    std::vector<RecordingNode> tree(1);
    std::vector<Pending> stack{{0, 0, learned_[0].energy, 1}};
    while (!stack.empty() && total_ > 0) {
        const Pending p = stack.back();
        stack.pop_back();
        for (int q = 0; q < 4; ++q) {
            if (!(p.energy[q] > threshold * total_) || p.depth >= max_depth) continue;
            const uint32_t child = uint32_t(tree.size());
            tree.emplace_back();
            tree[p.node].child[q] = child;
            const uint32_t source = p.learned >= 0 ? learned_[size_t(p.learned)].child[q] : 0;
            std::array<double, 4> energy;
            energy.fill(p.energy[q] / 4);
            if (source != 0) energy = learned_[source].energy;
            stack.push_back({child, source != 0 ? int64_t(source) : -1, energy, p.depth + 1});
        }
    }
    recording_ = std::move(tree);
}

}  // namespace glint
