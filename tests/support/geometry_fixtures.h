// Geometry fixtures shared by the BVH's tests and the spatial splits' check in bench/: random
// scenes, a grid of shared edges, answers compared with testing every primitive, and the wide
// tree's SAH cost against the least a plain dynamic programme finds.
#pragma once

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <vector>

#include "accel/bvh_collapse.h"
#include "base/rng.h"
#include "scene/geometry.h"

namespace glint::testing {

struct RandomScene {
    std::vector<Sphere> spheres;
    std::vector<Triangle> triangles;
};

inline RandomScene random_scene(uint64_t seed, int spheres, int triangles) {
    Rng rng(seed, 0, 0);
    auto point = [&] { return Vec3{rng.uniform(), rng.uniform(), rng.uniform()} * 20 - Vec3{10}; };
    RandomScene s;
    for (int i = 0; i < spheres; ++i) s.spheres.push_back({point(), 0.05 + rng.uniform()});
    for (int i = 0; i < triangles; ++i) {
        const Vec3 a = point();
        s.triangles.push_back({a, a + (point() * 0.1), a + (point() * 0.1)});
    }
    return s;
}

// A grid of unit squares in the z = 0 plane, two triangles each: its node boxes share planes.
inline std::vector<Triangle> grid(int n) {
    std::vector<Triangle> out;
    for (int i = 0; i < n; ++i)
        for (int j = 0; j < n; ++j) {
            const Vec3 a{double(i), double(j), 0}, b{i + 1.0, double(j), 0}, c{i + 1.0, j + 1.0, 0}, d{double(i), j + 1.0, 0};
            out.push_back({a, b, c});
            out.push_back({a, c, d});
        }
    return out;
}

// Scene: Geometry, or another type with its queries (the benchmarks' SplitGeometry).
template <typename Scene>
void expect_same_answers(const Scene& bvh, const Geometry& list, const Ray& ray) {
    Hit a, b;
    const bool hit_a = bvh.intersect(ray, kNoPrimitive, a), hit_b = list.intersect(ray, kNoPrimitive, b);
    ASSERT_EQ(hit_a, hit_b);
    EXPECT_EQ(bvh.occluded(ray, kNoPrimitive), hit_b);
    if (!hit_a) return;
    EXPECT_EQ(a.t, b.t);  // bit for bit: the same primitive test decides
    if (a.prim == b.prim) return;
    // A ray through a shared edge or vertex meets several primitives at the same t; either
    // answer is right, but it must be a true tie.
    Hit tie;
    Ray only_b = ray;
    only_b.tmax = b.t;
    ASSERT_FALSE(list.is_sphere(a.prim));
    ASSERT_TRUE(list.triangle(a.prim).intersect(only_b, tie.triangle));
    EXPECT_EQ(tie.triangle.t, b.t);
}

// The SAH cost of the wide tree collapse_to_wide() makes of `tree`.
inline double wide_cost(const BinaryTree& tree) {
    const std::vector<BvhNode> nodes = collapse_to_wide(tree.nodes);
    double cost = tree.nodes[0].half_area();
    for (const BvhNode& n : nodes)
        for (int slot = 0; slot < kBvhWidth; ++slot)
            if (n.used(slot)) cost += (ChildRef::count(n.child[slot]) > 0 ? double(kLeafCost) : 1.0) * n.half_area(slot);
    return cost;
}

// The least SAH cost of any wide tree over `binary`: a plain scalar dynamic programme.
inline double least_wide_cost(const std::vector<BinaryNode>& binary) {
    std::vector<std::array<double, kBvhWidth + 1>> cost(binary.size());  // cost[n][slots], 1..W
    std::vector<uint32_t> prims(binary.size());
    const auto split = [&](uint32_t n, int slots) {
        double best = kInfinity;
        for (int k = 1; k < slots; ++k) best = std::min(best, cost[binary[n].first][k] + cost[binary[n].first + 1][slots - k]);
        return best;
    };
    for (size_t n = binary.size(); n-- > 0;) {
        const double area = binary[n].half_area(), leaf = double(kLeafCost) * area;
        if (binary[n].is_leaf()) {
            prims[n] = binary[n].count;
            cost[n].fill(leaf);
            continue;
        }
        prims[n] = prims[binary[n].first] + prims[binary[n].first + 1];
        const double node = area + split(uint32_t(n), kBvhWidth);
        cost[n][1] = prims[n] <= BinaryTree::kMaxLeafSize ? std::min(leaf, node) : node;
        for (int slots = 2; slots <= kBvhWidth; ++slots) cost[n][slots] = std::min(cost[n][slots - 1], split(uint32_t(n), slots));
    }
    return binary[0].half_area() + split(0, kBvhWidth);
}

}  // namespace glint::testing
