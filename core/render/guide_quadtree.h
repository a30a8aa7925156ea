// The directional half of the path guide (path_guide.h): a quadtree over the unit square onto
// which the sphere of directions is mapped by an equal-area cylindrical map, each node holding
// the energy of its four quadrants (Müller et al. 2017, "Practical Path Guiding"). It holds two
// distributions, each over its own tree: the one it samples, learned in the last training
// iteration, and the one it records in the current iteration, refined to the first. Recording adds fixed-point integers, so the
// sums, and all that is learned from them, do not depend on the order in which threads record.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "base/math.h"

namespace glint {

// The equal-area map: x = (1 + d.y) / 2, y = φ / 2π with φ = atan2(d.z, d.x) in [0, 2π).
// A density over the square is 4π times the density over the sphere.
struct SquarePoint {
    double x = 0, y = 0;
};
SquarePoint direction_to_square(const Vec3& d);
Vec3 square_to_direction(const SquarePoint& s);

// A sum of non-negative fixed-point amounts, 128 bits wide, that threads add to without a lock
// and that comes out the same whatever the order of the additions.
struct ExactSum {
    uint64_t lo = 0, hi = 0;
    void add(uint64_t amount);  // thread-safe
    double value() const;       // in the amounts' units
};

class GuideQuadtree {
public:
    // A recorded amount is stored in units of 2^-kFractionBits, and at most kMaxAmount.
    static constexpr int kFractionBits = 32;
    static constexpr double kMaxAmount = 0x1p30;

    GuideQuadtree();  // one node, nothing learned or recorded

    // Thread-safe: adds `amount` (≥ 0) to the recorded energy of every quadrant that holds s.
    void record(const SquarePoint& s, double amount);
    // The learned distribution: whether it holds any energy; its density over the square at s;
    // a point drawn from it with (u1, u2) and its density.
    bool learned() const { return total_ > 0; }
    double pdf(const SquarePoint& s) const;
    SquarePoint sample(double u1, double u2, double& pdf) const;

    // Ends an iteration: what was recorded becomes the learned distribution, and recording
    // starts again from zero over a structure refined to it: a quadrant is split while it holds
    // more than `threshold` of the energy and is less than `max_depth` levels deep, and its
    // children merged where it holds less.
    void learn_and_refine(double threshold, int max_depth);
    size_t nodes() const { return learned_.size() + recording_.size(); }
    size_t bytes() const { return learned_.size() * sizeof(LearnedNode) + recording_.size() * sizeof(RecordingNode); }

private:
    // Quadrant q of a node is [x, x + 1/2) × [y, y + 1/2) with x = (q & 1) / 2, y = (q >> 1) / 2;
    // child[q] 0: that quadrant is a leaf (node 0 is the root).
    struct LearnedNode {
        std::array<uint32_t, 4> child{};
        std::array<double, 4> energy{};
    };
    struct RecordingNode {
        std::array<uint32_t, 4> child{};
        std::array<ExactSum, 4> energy{};
    };
    // The quadrant of a node's local (x, y), which it turns into the quadrant's local coordinates.
    static int quadrant(double& x, double& y);
    void refine(double threshold, int max_depth);

    std::vector<LearnedNode> learned_;
    std::vector<RecordingNode> recording_;
    double total_ = 0;  // of the learned distribution
};

}  // namespace glint
