// Checks of the spatial splits (spatial_splits.h), which only the benchmarks build: the clipping
// they rely on, the collapse of their tree at least cost, and the split tree answering every
// ray exactly as testing every triangle does. Run by hand, as the benchmarks are:
//   build/bench/spatial_splits_check
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "base/rng.h"
#include "base/sampling.h"
#include "spatial_splits.h"
#include "support/geometry_fixtures.h"

namespace glint {
namespace {

using testing::expect_same_answers;
using testing::grid;
using testing::least_wide_cost;
using testing::random_scene;
using testing::RandomScene;
using testing::wide_cost;

// Spatial splits rely on it: every point of the triangle inside the box lies in the clipped
// box, which lies in the box; a box the triangle misses gives an empty one or a sliver.
TEST(SpatialSplits, ClippedBoundsHoldThePartInsideTheBox) {
    Rng rng(31, 0, 0);
    auto point = [&](double scale) { return (Vec3{rng.uniform(), rng.uniform(), rng.uniform()} * 2 - Vec3{1}) * scale; };
    int inside = 0;
    for (int i = 0; i < 2000; ++i) {
        // Far-off and huge triangles too: the padding must follow the vertices' magnitude.
        const double scale = i % 4 == 0 ? 1e6 : 1;
        const Triangle t{point(scale), point(scale), point(scale)};
        const Vec3 c = point(0.5);
        const Bounds3 box{c - Vec3{rng.uniform() * 0.5}, c + Vec3{rng.uniform() * 0.5}};
        const Bounds3 part = clipped_bounds(t, box);
        if (!part.empty())
            for (int a = 0; a < 3; ++a) {
                EXPECT_GE(part.lo[a], box.lo[a]);
                EXPECT_LE(part.hi[a], box.hi[a]);
            }
        for (int k = 0; k < 200; ++k) {
            const double u = rng.uniform(), v = rng.uniform() * (1 - u);
            const Vec3 p = t.v0 * (1 - u - v) + t.v1 * u + t.v2 * v;
            if (!(p.x >= box.lo.x && p.x <= box.hi.x && p.y >= box.lo.y && p.y <= box.hi.y && p.z >= box.lo.z && p.z <= box.hi.z))
                continue;
            ++inside;
            ASSERT_FALSE(part.empty());
            for (int a = 0; a < 3; ++a) {
                EXPECT_GE(p[a], part.lo[a]);
                EXPECT_LE(p[a], part.hi[a]);
            }
        }
    }
    EXPECT_GT(inside, 1000);  // the test saw many points inside
}

// The spatial splits' cost estimate: a slab's box is the clipped box of the slab (unbounded
// across it) but for rounding, for slabs through the triangle, beside it and holding a vertex.
TEST(SpatialSplits, SlabBoundsAreTheClippedBoundsOfTheSlab) {
    Rng rng(37, 0, 0);
    auto point = [&]() { return Vec3{rng.uniform(), rng.uniform(), rng.uniform()} * 2 - Vec3{1}; };
    int nonempty = 0;
    for (int i = 0; i < 2000; ++i) {
        const Triangle t{point(), point(), point()};
        const int axis = i % 3;
        const double lower = rng.uniform() * 2.2 - 1.1, upper = lower + rng.uniform() * 0.5;
        Bounds3 slab{Vec3{-kInfinity}, Vec3{kInfinity}};
        slab.lo[axis] = lower;
        slab.hi[axis] = upper;
        const Bounds3 exact = clipped_bounds(t, slab), estimate = slab_bounds(t, axis, lower, upper);
        ASSERT_EQ(exact.empty(), estimate.empty()) << i;
        if (exact.empty()) continue;
        ++nonempty;
        for (int a = 0; a < 3; ++a) {
            EXPECT_NEAR(estimate.lo[a], exact.lo[a], 1e-12) << i;
            EXPECT_NEAR(estimate.hi[a], exact.hi[a], 1e-12) << i;
        }
    }
    EXPECT_GT(nonempty, 500);
}

// The wide tree over the split tree costs the least there is (as Bvh.CollapseFindsTheLeastCost
// checks for the binned tree): the split tree's leaves are single triangles the collapse merges.
TEST(SpatialSplits, CollapseFindsTheLeastCost) {
    const RandomScene s = random_scene(19, 0, 4000);
    std::vector<Bounds3> bounds;
    for (const Triangle& t : s.triangles) bounds.push_back(t.bounds());
    const BinaryTree tree = build_sah_tree(bounds, SpatialSplits(s.triangles));
    EXPECT_NEAR(wide_cost(tree), least_wide_cost(tree.nodes), 1e-5 * wide_cost(tree));
}

// Long triangles across the scene, in every orientation, among small ones: spatial splits cut
// them into several leaves, and the tree must still answer as testing every triangle does,
// also for rays leaving a triangle (which no copy of it may stop) and shadow rays to one.
TEST(SpatialSplits, TreeAnswersAsBruteForce) {
    RandomScene s = random_scene(17, 0, 3000);
    Rng rng(18, 0, 0);
    auto point = [&] { return Vec3{rng.uniform(), rng.uniform(), rng.uniform()} * 20 - Vec3{10}; };
    for (int i = 0; i < 300; ++i) s.triangles.push_back({point(), point(), point()});
    const SplitGeometry split(s.triangles);
    const Geometry list({}, s.triangles, Accelerator::list);
    const Bvh& bvh = split.triangle_bvh();
    ASSERT_GT(bvh.tree_size(), s.triangles.size() + 300) << "the long triangles should be split";
    // Every position lies in one leaf, and every triangle is in the tree.
    std::vector<int> seen(bvh.tree_size(), 0);
    bvh.for_each_leaf([&](uint32_t first, uint32_t count) {
        for (uint32_t k = first; k < first + count; ++k) ++seen[k];
    });
    for (int count : seen) EXPECT_EQ(count, 1);
    std::vector<uint32_t> order(bvh.order());
    std::sort(order.begin(), order.end());
    order.erase(std::unique(order.begin(), order.end()), order.end());
    EXPECT_EQ(order.size(), s.triangles.size());

    for (int i = 0; i < 20000; ++i) {
        const Vec3 o = Vec3{rng.uniform(), rng.uniform(), rng.uniform()} * 30 - Vec3{15};
        expect_same_answers(split, list, Ray{o, sample_uniform_sphere(rng.uniform(), rng.uniform()), i % 3 == 0 ? -kInfinity : 0.0});
    }
    for (int i = 0; i < 5000; ++i) {
        // From a point on one of the long triangles, with that triangle as `self`.
        const auto self = static_cast<uint32_t>(3000 + rng.uniform() * 300);
        const Triangle& t = s.triangles[self];
        const double u = rng.uniform(), v = rng.uniform() * (1 - u);
        const Ray ray{t.v0 * (1 - u - v) + t.v1 * u + t.v2 * v, sample_uniform_sphere(rng.uniform(), rng.uniform())};
        Hit a, b;
        ASSERT_EQ(split.intersect(ray, self, a), list.intersect(ray, self, b));
        EXPECT_NE(a.prim, self);
        EXPECT_EQ(a.t, b.t);
        const auto target = static_cast<uint32_t>(rng.uniform() * 3300);
        EXPECT_EQ(split.occluded(ray, self, target), list.occluded(ray, self, target));
    }
}

TEST(SpatialSplits, TreeKeepsAxisParallelRaysOnSharedEdges) {
    std::vector<Triangle> triangles = grid(32);
    triangles.push_back({{0, 0, 0.5}, {32, 32, 0.5}, {0, 32.5, 0.25}});  // a long one above, to split
    const SplitGeometry bvh(triangles);
    const Geometry list({}, triangles, Accelerator::list);
    Rng rng(19, 0, 0);
    for (int i = 0; i < 3000; ++i) {
        const Vec3 o{std::floor(rng.uniform() * 33), std::floor(rng.uniform() * 33), rng.uniform() < 0.5 ? 1.0 : -1.0};
        for (double zero : {0.0, -0.0}) {
            expect_same_answers(bvh, list, Ray{o, {zero, zero, -o.z}});
            expect_same_answers(bvh, list, Ray{o, normalize(Vec3{1, zero, -o.z})});
        }
    }
}

}  // namespace
}  // namespace glint
