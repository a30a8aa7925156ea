// Path guiding: where light comes from at each region of the scene, learned while rendering, so
// that a path's bounces can be drawn towards it (guided_bsdf.h mixes it with the BSDF). An
// SD-tree (Müller et al. 2017, "Practical Path Guiding"): a binary tree over the scene's bounds
// whose leaves each hold a directional quadtree (guide_quadtree.h) of the radiance arriving there.
//
// It learns in iterations: each records the radiance that its paths carry back to their
// vertices, then learns it and refines itself, the next sampling from what the last learned. A
// leaf splits in two when it recorded more than spatial_threshold · √(iteration's paths / 10⁶)
// vertices (its quadtree copied to both halves); a quadrant splits where it holds more than
// directional_threshold of its leaf's energy. Recording is integer addition and refinement
// runs in tree order between iterations, so what the guide learns does not depend on threads.
#pragma once

#include <cstdint>
#include <vector>

#include "base/bounds.h"
#include "render/guide_quadtree.h"

namespace glint {

struct GuideConfig {
    double mixture = 0.5;                 // the guide's share of the bounces at a guided vertex
    double spatial_threshold = 12000;     // Müller et al.'s c, per 10⁶ paths of an iteration
    double directional_threshold = 0.01;  // Müller et al.'s ρ
    int max_directional_depth = 20;
    size_t max_leaves = size_t(1) << 14;  // bounds the spatial tree, and so the memory
    // Training iterations trace 1, 2, 4, ... paths per pixel of the image; as many iterations
    // as fit in training_share of the job's samples, at most max_iterations.
    double training_share = 0.125;
    int max_iterations = 6;
};

// What a guide holds: its size, for memory reports.
struct GuideStats {
    size_t spatial_nodes = 0, leaves = 0, directional_nodes = 0, bytes = 0;
};

class PathGuide {
public:
    PathGuide(const Bounds3& scene_bounds, const GuideConfig& config = {});

    // Thread-safe: radiance `amount` (its luminance over the density with which wi was drawn)
    // arriving at p from direction wi.
    void record(const Vec3& p, const Vec3& wi, double amount);
    // The directional distribution learned around p, or nullptr before anything is learned there.
    const GuideQuadtree* at(const Vec3& p) const;
    // Ends an iteration of `paths` paths.
    void learn(uint64_t paths);

    const GuideConfig& config() const { return config_; }
    GuideStats stats() const;

private:
    struct Node {
        uint32_t child = 0;  // the first of two children (0: a leaf)
        uint8_t axis = 0;
        double split = 0;
        uint32_t leaf = 0;  // with no children: leaves_'s index
    };
    struct Leaf {
        GuideQuadtree directions;
        uint64_t records = 0;  // this iteration's, added atomically
    };
    uint32_t leaf_at(const Vec3& p) const;  // leaves_'s index
    // Splits node `node` (a leaf over `box`) while its share of the records is above `threshold`.
    void split(uint32_t node, const Bounds3& box, double records, double threshold);

    GuideConfig config_;
    Bounds3 bounds_;
    std::vector<Node> nodes_;
    std::vector<Leaf> leaves_;
};

// How many training iterations a job of `job_spp` samples per pixel trains (GuideConfig).
int guide_iterations(const GuideConfig& config, uint32_t job_spp);

}  // namespace glint
