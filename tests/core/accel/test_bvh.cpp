// The BVH must answer exactly as testing every primitive does: same primitive, same t, for
// random rays, axis-parallel rays with signed zeros, and rays starting on node planes.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <cstring>

#include "accel/bvh_collapse.h"
#include "scene/geometry.h"
#include "base/rng.h"
#include "base/sampling.h"
#include "support/geometry_fixtures.h"

namespace glint {
namespace {

using testing::expect_same_answers;
using testing::grid;
using testing::least_wide_cost;
using testing::wide_cost;
using testing::random_scene;
using testing::RandomScene;

// Every third ray has tmin = -inf, and so takes the traversal with the slab box test (the
// others take the fused one): it must find hits behind the origin too.
TEST(Bvh, MatchesBruteForceOnRandomRays) {
    const RandomScene s = random_scene(11, 200, 3000);
    const Geometry bvh(s.spheres, s.triangles, Accelerator::bvh), list(s.spheres, s.triangles, Accelerator::list);
    Rng rng(12, 0, 0);
    for (int i = 0; i < 20000; ++i) {
        const Vec3 o = Vec3{rng.uniform(), rng.uniform(), rng.uniform()} * 30 - Vec3{15};
        const Ray ray{o, sample_uniform_sphere(rng.uniform(), rng.uniform()), i % 3 == 0 ? -kInfinity : 0.0};
        expect_same_answers(bvh, list, ray);
    }
}

TEST(Bvh, AxisParallelRaysWithSignedZerosOnNodePlanes) {
    const std::vector<Triangle> triangles = grid(32);
    const Geometry bvh({}, triangles, Accelerator::bvh), list({}, triangles, Accelerator::list);
    Rng rng(13, 0, 0);
    for (int i = 0; i < 5000; ++i) {
        // Origins on integer coordinates lie exactly on the planes of many node boxes.
        const Vec3 o{std::floor(rng.uniform() * 33), std::floor(rng.uniform() * 33), rng.uniform() < 0.5 ? 1.0 : -1.0};
        for (double zero : {0.0, -0.0}) {
            expect_same_answers(bvh, list, Ray{o, {zero, zero, -o.z}});       // straight down onto shared vertices
            expect_same_answers(bvh, list, Ray{{o.x, o.y, 0}, {1, zero, zero}});  // in the plane: no hit
            expect_same_answers(bvh, list, Ray{o, normalize(Vec3{1, zero, -o.z})});
        }
    }
    // Straight down onto a vertex, the answer is a hit at t = 1 exactly.
    Hit hit;
    ASSERT_TRUE(bvh.intersect(Ray{{5, 5, 1}, {-0.0, 0.0, -1}}, kNoPrimitive, hit));
    EXPECT_EQ(hit.t, 1);
}

// The AVX-512 instantiation of the triangle queries answers bit for bit as the AVX2 one (same
// triangle, t and barycentrics; same any-hit answers), through the tree and through the list, on
// random rays and on axis-parallel rays with signed zeros aimed at the shared edges and vertices
// of a grid. Elsewhere the tests run whichever path best_isa() picks; this one also runs AVX2.
TEST(Bvh, Avx512PathAnswersBitForBitAsAvx2) {
    if (best_isa() != Isa::avx512) GTEST_SKIP() << "this processor has no AVX-512VL";
    RandomScene s = random_scene(18, 0, 3000);
    for (const Triangle& t : grid(16)) s.triangles.push_back(t);
    auto bits = [](double x) { return std::bit_cast<uint64_t>(x); };
    for (Accelerator accelerator : {Accelerator::bvh, Accelerator::list}) {
        Geometry avx2({}, s.triangles, accelerator), avx512({}, s.triangles, accelerator);
        avx2.set_isa(Isa::avx2);
        avx512.set_isa(Isa::avx512);
        auto expect_same = [&](const Ray& ray) {
            Hit a, b;
            ASSERT_EQ(avx2.intersect(ray, kNoPrimitive, a), avx512.intersect(ray, kNoPrimitive, b));
            EXPECT_EQ(a.prim, b.prim);
            for (auto [x, y] : {std::pair{a.t, b.t}, {a.triangle.b0, b.triangle.b0}, {a.triangle.b1, b.triangle.b1},
                                {a.triangle.b2, b.triangle.b2}})
                EXPECT_EQ(bits(x), bits(y));
            EXPECT_EQ(avx2.occluded(ray, kNoPrimitive), avx512.occluded(ray, kNoPrimitive));
        };
        Rng rng(19, 0, 0);
        int hits = 0;
        for (int i = 0; i < 5000; ++i) {
            const Vec3 o = Vec3{rng.uniform(), rng.uniform(), rng.uniform()} * 30 - Vec3{15};
            const Ray ray{o, sample_uniform_sphere(rng.uniform(), rng.uniform())};
            expect_same(ray);
            const Vec3 vertex{std::floor(rng.uniform() * 17), std::floor(rng.uniform() * 17), 0};
            for (double zero : {0.0, -0.0}) {
                expect_same(Ray{vertex + Vec3{0, 0, 2}, {zero, zero, -1}});
                expect_same(Ray{vertex + Vec3{0.5, 0, 3}, normalize(Vec3{zero, 0.25, -1})});  // onto an edge
            }
            Hit unused;
            hits += avx2.intersect(ray, kNoPrimitive, unused);
        }
        EXPECT_GT(hits, 500);
    }
}

// Both box tests are conservative: a box rounded outward around a point of the double ray, a
// float ulp or two wide (the tightest boxes there are, so the padding of the far distances
// is all that keeps them: without it most of these fail), is never rejected, whatever the
// ray's origin, direction (axis-parallel, signed zeros) and distance to the point. The points
// lie as close as 10^-4 of the origin's magnitude, where rounding o·inv to nearest instead of
// outward would lose the fused test boxes.
TEST(Bvh, BoxTestNeverRejectsATightBoxAroundAPointOfTheRay) {
    Rng rng(20, 0, 0);
    int fused = 0;
    for (int i = 0; i < 20000; ++i) {
        const double scale = std::pow(10.0, rng.uniform() * 8 - 3);
        const Vec3 o = (Vec3{rng.uniform(), rng.uniform(), rng.uniform()} * 2 - Vec3{1}) * scale;
        Vec3 d = sample_uniform_sphere(rng.uniform(), rng.uniform());
        if (i % 4 == 1) d[i % 3] = i % 8 == 1 ? 0.0 : -0.0;
        const Ray ray{o, d, i % 3 == 0 ? -kInfinity : 0.0, kInfinity};
        WideBox box;
        for (int slot = 0; slot < kBoxLanes; ++slot) {
            const double t = std::pow(10.0, rng.uniform() * 8 - 4) * scale;
            for (int a = 0; a < 3; ++a) {
                // o + d·t in double is off the exact point by less than `error`.
                const double p = o[a] + d[a] * t, error = (std::fabs(o[a]) + std::fabs(d[a] * t)) * 0x1p-51;
                box.planes[2 * a][slot] = to_float_down(p - error);
                box.planes[2 * a + 1][slot] = to_float_up(p + error);
            }
        }
        const __m256 tmax = _mm256_set1_ps(std::numeric_limits<float>::infinity());
        __m256 entry;
        EXPECT_EQ(RayBoxTest(ray).hit(box, tmax, entry), 0xFF) << "ray " << i;
        if (!FusedRayBoxTest::covers(ray)) continue;
        ++fused;
        EXPECT_EQ(FusedRayBoxTest(ray).hit(box, tmax, entry), 0xFF) << "ray " << i;
    }
    EXPECT_GT(fused, 9000);
}

// The fused test covers the rays of a render and leaves the others to the slab test: a zero
// direction component (its reciprocal is infinite), tmin < 0 or NaN, magnitudes whose products
// could leave float's range.
TEST(Bvh, FusedBoxTestCoversOrdinaryRaysOnly) {
    const Vec3 o{1, 2, 3}, d = normalize(Vec3{1, -2, 3});
    EXPECT_TRUE(FusedRayBoxTest::covers(Ray{o, d}));
    EXPECT_TRUE(FusedRayBoxTest::covers(Ray{{0, 0, 0}, d, 0.5, 7}));
    EXPECT_TRUE(FusedRayBoxTest::covers(Ray{o, d, -0.0}));
    EXPECT_FALSE(FusedRayBoxTest::covers(Ray{o, {0.0, 0.6, 0.8}}));
    EXPECT_FALSE(FusedRayBoxTest::covers(Ray{o, {0.6, -0.0, 0.8}}));
    EXPECT_FALSE(FusedRayBoxTest::covers(Ray{o, {1e-30, 0.6, 0.8}}));
    EXPECT_FALSE(FusedRayBoxTest::covers(Ray{o, d, -1}));
    EXPECT_FALSE(FusedRayBoxTest::covers(Ray{o, d, std::numeric_limits<double>::quiet_NaN()}));
    EXPECT_FALSE(FusedRayBoxTest::covers(Ray{{1e30, 0, 0}, d}));
}

// The interval of t in which the ray crosses box `slot`, in double: empty when lo > hi.
std::pair<double, double> exact_slab(const Ray& ray, const WideBox& box, int slot) {
    double lo = ray.tmin, hi = ray.tmax;
    for (int a = 0; a < 3; ++a) {
        double t0 = (box.planes[2 * a][slot] - ray.o[a]) / ray.d[a], t1 = (box.planes[2 * a + 1][slot] - ray.o[a]) / ray.d[a];
        if (t0 > t1) std::swap(t0, t1);
        lo = std::max(lo, t0);
        hi = std::min(hi, t1);
    }
    return {lo, hi};
}

// The fused test is not merely conservative: on boxes around points near the ray it accepts
// the boxes the slab test accepts, but for boxes that the ray misses or meets by a hair (within
// a few float ulps of the origin's coordinates, as seen along the ray), and its entry distances
// agree with the slab test's to that precision.
TEST(Bvh, FusedBoxTestAgreesWithTheSlabTest) {
    Rng rng(21, 0, 0);
    int accepted = 0, rejected = 0;
    for (int i = 0; i < 5000; ++i) {
        const Ray ray{Vec3{rng.uniform(), rng.uniform(), rng.uniform()} * 20 - Vec3{10},
                      sample_uniform_sphere(rng.uniform(), rng.uniform()), i % 2 ? 0.0 : -0.0, 5 + 20 * rng.uniform()};
        WideBox box;
        for (int slot = 0; slot < kBoxLanes; ++slot) {
            const Vec3 near_ray = ray.o + ray.d * (rng.uniform() * 30 - 3);
            for (int a = 0; a < 3; ++a) {
                const double lo = near_ray[a] + rng.uniform() * 2 - 1.5;
                box.planes[2 * a][slot] = to_float_down(lo);
                box.planes[2 * a + 1][slot] = to_float_up(lo + rng.uniform() * 2);
            }
        }
        const __m256 tmax = _mm256_set1_ps(to_float_up(ray.tmax));
        alignas(32) float slab_entry[kBoxLanes], fused_entry[kBoxLanes];
        __m256 e;
        const int slab = RayBoxTest(ray).hit(box, tmax, e);
        _mm256_store_ps(slab_entry, e);
        const int fused = FusedRayBoxTest(ray).hit(box, tmax, e);
        _mm256_store_ps(fused_entry, e);
        // A few float ulps of the origin, in t.
        const double steepest = std::min({std::fabs(ray.d.x), std::fabs(ray.d.y), std::fabs(ray.d.z)});
        const double hair = 1e-6 * (1 + max_component(abs(ray.o))) / steepest;
        const auto disagree = static_cast<unsigned>(slab ^ fused), both = static_cast<unsigned>(slab & fused);
        for (int slot = 0; slot < kBoxLanes; ++slot) {
            if (disagree >> slot & 1) {
                const auto [lo, hi] = exact_slab(ray, box, slot);
                EXPECT_LT(std::fabs(hi - lo), hair) << "ray " << i << " slot " << slot;
            }
            if (both >> slot & 1) {
                EXPECT_NEAR(fused_entry[slot], std::max(slab_entry[slot], 0.0f), hair) << "ray " << i;
            }
        }
        accepted += std::popcount(static_cast<unsigned>(slab));
        rejected += kBoxLanes - std::popcount(static_cast<unsigned>(slab));
    }
    EXPECT_GT(accepted, 5000);
    EXPECT_GT(rejected, 5000);
}

// Doubles that try a rounding to float: signed zeros, subnormals, float's range limits,
// infinities, and random values of every magnitude from the stream `seed`.
std::vector<double> directed_rounding_values(uint64_t seed) {
    constexpr double kMaxF = std::numeric_limits<float>::max();
    std::vector<double> values = {0.0, -0.0, 1.0, -1.0, 0.1, -0.1, 1e-45, -1e-45, 1e-310, -1e-310, 1e-39, kMaxF,
                                  -kMaxF, kMaxF * (1 + 0x1p-30), -kMaxF * (1 + 0x1p-30), 1e39, -1e39, kInfinity, -kInfinity};
    Rng rng(seed, 0, 0);
    for (int i = 0; i < 4000; ++i) values.push_back((rng.uniform() - 0.5) * std::pow(10.0, rng.uniform() * 90 - 45));
    return values;
}

// The four-wide directed roundings of a ray's setup agree bit for bit with the scalar ones,
// which bracket the double: on signed zeros, subnormals, float's range limits, infinities, NaN
// and random values of every magnitude.
TEST(Bvh, FourWideDirectedRoundingMatchesScalar) {
    const std::vector<double> values = directed_rounding_values(17);
    auto same = [](float a, float b) { return std::bit_cast<uint32_t>(a) == std::bit_cast<uint32_t>(b); };
    for (size_t i = 0; i < values.size(); i += 4) {
        double v[4];
        for (int k = 0; k < 4; ++k) v[k] = values[std::min(i + k, values.size() - 1)];
        alignas(16) float up[4], down[4];
        _mm_store_ps(up, to_float_up(_mm256_loadu_pd(v)));
        _mm_store_ps(down, to_float_down(_mm256_loadu_pd(v)));
        for (int k = 0; k < 4; ++k) {
            EXPECT_TRUE(same(up[k], to_float_up(v[k]))) << v[k];
            EXPECT_TRUE(same(down[k], to_float_down(v[k]))) << v[k];
            EXPECT_LE(double(down[k]), v[k]);
            EXPECT_GE(double(up[k]), v[k]);
        }
    }
    alignas(16) float nan[4];
    _mm_store_ps(nan, to_float_up(_mm256_set1_pd(std::numeric_limits<double>::quiet_NaN())));
    EXPECT_TRUE(std::isnan(nan[0]));
}

// The traversal's one-instruction rounding after a hit (AVX-512 only) is the scalar rounding bit
// for bit, on the same special and random values.
TEST(Bvh, EmbeddedRoundingMatchesScalar) {
    if (best_isa() != Isa::avx512) GTEST_SKIP() << "no AVX-512VL here";
    for (double v : directed_rounding_values(19))
        EXPECT_EQ(std::bit_cast<uint32_t>(to_float_up_avx512(v)), std::bit_cast<uint32_t>(to_float_up(v))) << v;
    EXPECT_TRUE(std::isnan(to_float_up_avx512(std::numeric_limits<double>::quiet_NaN())));
}

TEST(Bvh, NanRaysTerminateWithoutAHit) {
    const RandomScene s = random_scene(14, 50, 500);
    const Geometry bvh(s.spheres, s.triangles);
    const double nan = std::numeric_limits<double>::quiet_NaN();
    Hit hit;
    EXPECT_FALSE(bvh.intersect(Ray{{0, 0, 0}, {nan, 0, 1}}, kNoPrimitive, hit));
    EXPECT_FALSE(bvh.intersect(Ray{{nan, 0, 0}, {0, 0, 1}}, kNoPrimitive, hit));
    EXPECT_FALSE(bvh.occluded(Ray{{0, 0, 0}, {nan, nan, nan}}, kNoPrimitive));
}

// Each of the six coordinates alone, NaN or infinite, makes the ray non-finite; tmin and tmax
// (an infinite tmax is every camera ray's) do not.
TEST(Bvh, FiniteOriginAndDirectionLooksAtEachCoordinate) {
    const double bad[3] = {std::numeric_limits<double>::quiet_NaN(), kInfinity, -kInfinity};
    EXPECT_TRUE(has_finite_origin_and_direction(Ray{{1, -2, 3}, {0, 0.6, -0.8}, -kInfinity, kInfinity}));
    for (int coordinate = 0; coordinate < 6; ++coordinate)
        for (double value : bad) {
            Ray ray{{1, -2, 3}, {0, 0.6, -0.8}};
            Vec3& v = coordinate < 3 ? ray.o : ray.d;
            (coordinate % 3 == 0 ? v.x : coordinate % 3 == 1 ? v.y : v.z) = value;
            EXPECT_FALSE(has_finite_origin_and_direction(ray)) << "coordinate " << coordinate << " = " << value;
        }
}

TEST(Bvh, TreeIsWellFormed) {
    const RandomScene s = random_scene(15, 100, 5000);
    const Geometry g(s.spheres, s.triangles);
    for (const Bvh* bvh : {&g.sphere_bvh(), &g.triangle_bvh()}) {
        // Every position of the tree lies in exactly one leaf, every node but the root has one
        // parent, and every child's box lies in the box its parent keeps for it.
        std::vector<int> seen(bvh->tree_size(), 0), parents(bvh->nodes().size(), 0);
        for (const BvhNode& n : bvh->nodes())
            for (int slot = 0; slot < kBvhWidth; ++slot) {
                const bool used = n.used(slot);
                if (!used) continue;
                const uint32_t ref = n.child[slot], count = ChildRef::count(ref);
                if (count > 0) {
                    EXPECT_LE(count, BinaryTree::kMaxLeafSize);
                    for (uint32_t k = ChildRef::first(ref); k < ChildRef::first(ref) + count; ++k) ++seen[k];
                    continue;
                }
                const uint32_t index = ChildRef::node_index(ref);
                ASSERT_EQ(ChildRef::node(index), ref);
                const BvhNode& child = bvh->nodes()[index];
                ++parents[index];
                for (int c = 0; c < kBvhWidth; ++c) {
                    if (!child.used(c)) continue;
                    for (int a = 0; a < 3; ++a) {
                        EXPECT_GE(child.plane(2 * a, c), n.plane(2 * a, slot));
                        EXPECT_LE(child.plane(2 * a + 1, c), n.plane(2 * a + 1, slot));
                    }
                }
            }
        for (int count : seen) EXPECT_EQ(count, 1);
        for (size_t i = 1; i < parents.size(); ++i) EXPECT_EQ(parents[i], 1) << "node " << i;
    }
    // Tree order is a permutation of the primitives.
    std::vector<uint32_t> order = g.triangle_bvh().order();
    std::sort(order.begin(), order.end());
    for (uint32_t i = 0; i < order.size(); ++i) EXPECT_EQ(order[i], i);
}

// The any-hit traversal takes children in slot order, so the builder stores the likeliest
// blockers first: the used slots lead, leaves before inner nodes, each group by falling area.
TEST(Bvh, ChildrenAreStoredLeavesFirstThenLargestFirst) {
    const RandomScene s = random_scene(16, 0, 5000);
    const Geometry g(s.spheres, s.triangles);
    int mixed = 0;  // nodes holding both leaves and inner nodes
    for (const BvhNode& n : g.triangle_bvh().nodes()) {
        const auto half_area = [&](int slot) { return n.half_area(slot); };
        const auto used = [&](int slot) { return n.used(slot); };
        const auto leaf = [&](int slot) { return ChildRef::count(n.child[slot]) > 0; };
        mixed += leaf(0) && !leaf(kBvhWidth - 1) && used(kBvhWidth - 1);
        for (int slot = 1; slot < kBvhWidth; ++slot) {
            if (!used(slot)) continue;
            ASSERT_TRUE(used(slot - 1)) << "slot " << slot;
            if (leaf(slot)) {
                ASSERT_TRUE(leaf(slot - 1)) << "slot " << slot;
            }
            if (leaf(slot) == leaf(slot - 1)) {
                EXPECT_LE(half_area(slot), half_area(slot - 1)) << "slot " << slot;
            }
        }
    }
    EXPECT_GT(mixed, 0);
}

// A binary tree where opening the largest child first wastes a node (W = kBvhWidth slots). The
// root (half area 1000) holds A (500) with two leaves and B (600), a chain of inner nodes B1 ..
// B(W-1) (600 down to 602 - W) with one leaf each and two under B(W-1): W + 2 leaves. Largest
// first opens B1 .. B(W-2) (all larger than A) until the root is full, leaving A and B(W-1) as
// nodes: three nodes. The least is two nodes: the root holds a1, a2, b1 .. b(W-3) and B(W-2),
// whose node holds the last three leaves (1000 + 603 - W).
TEST(Bvh, CollapseMakesTheNodesOfLeastArea) {
    const auto box = [](float area) { return FloatBox{{0, 0, 0}, {area, 1, 0}}; };  // half area: area
    const auto inner = [&](float area, uint32_t left) { return BinaryNode{box(area), left, 0}; };
    uint32_t position = 0;
    const auto leaf = [&] { return BinaryNode{box(1), position++, 1}; };
    std::vector<BinaryNode> binary = {inner(1000, 1), inner(500, 3), inner(600, 5), leaf(), leaf()};
    // b1 .. b(W-2) at 5 + 2k, and B2 .. B(W-1) at 6 + 2k with children from 7 + 2k on.
    for (int k = 0; k < kBvhWidth - 2; ++k) {
        binary.push_back(leaf());
        binary.push_back(inner(599.0f - float(k), static_cast<uint32_t>(binary.size()) + 1));
    }
    binary.push_back(leaf());  // b(W-1)
    binary.push_back(leaf());  // bW
    ASSERT_EQ(binary.size(), size_t(2 * kBvhWidth + 3));

    const std::vector<BvhNode> nodes = collapse_to_wide(binary);
    ASSERT_EQ(nodes.size(), 2u);
    const auto leaves = [](const BvhNode& n) {
        return std::count_if(std::begin(n.child), std::end(n.child), [](uint32_t c) { return ChildRef::count(c) > 0; });
    };
    EXPECT_EQ(leaves(nodes[0]), kBvhWidth - 1);
    EXPECT_EQ(leaves(nodes[1]), 3);
    int inner_children = 0;  // B(W-2) alone
    for (int slot = 0; slot < kBvhWidth; ++slot)
        if (ChildRef::count(nodes[0].child[slot]) == 0 && nodes[0].used(slot)) {
            ++inner_children;
            EXPECT_EQ(nodes[0].plane(1, slot), float(603 - kBvhWidth));
        }
    EXPECT_EQ(inner_children, 1);
}

// The collapse's SAH cost is the least there is: the wide tree of a random scene costs what a
// plain scalar dynamic programme over the same binary tree finds (every k, every slot count, in
// double), so the collapse's vector shortcuts lose nothing. (bench/spatial_splits_check.cpp
// checks the same of the tree with spatial splits.)
TEST(Bvh, CollapseFindsTheLeastCost) {
    const RandomScene s = random_scene(19, 0, 4000);
    std::vector<Bounds3> bounds;
    for (const Triangle& t : s.triangles) bounds.push_back(t.bounds());
    const BinaryTree tree = build_sah_tree(bounds);
    EXPECT_NEAR(wide_cost(tree), least_wide_cost(tree.nodes), 1e-5 * wide_cost(tree));
}

// Binary leaves become one leaf where that costs less. Under the root (half area 10), C (4)
// holds two leaves of 3 each, which overlap: one leaf of C costs 1.5 x 4 against 1.5 x 6 for the
// two. D (4) holds two leaves of 1: kept apart they cost 1.5 x 2, against 1.5 x 4 merged. The
// root then holds three slots: C as a leaf of two primitives, and D's two leaves.
TEST(Bvh, CollapseMergesLeavesWhereThatCostsLess) {
    const auto box = [](float area) { return FloatBox{{0, 0, 0}, {area, 1, 0}}; };
    const std::vector<BinaryNode> binary = {{box(10), 1, 0}, {box(4), 3, 0}, {box(4), 5, 0}, {box(3), 0, 1},
                                            {box(3), 1, 1},  {box(1), 2, 1}, {box(1), 3, 1}};
    const std::vector<BvhNode> nodes = collapse_to_wide(binary);
    ASSERT_EQ(nodes.size(), 1u);
    const BvhNode& root = nodes[0];
    // Leaves first, each group by falling area: C's merged leaf, then D's two.
    EXPECT_EQ(root.child[0], ChildRef::leaf(0, 2));
    EXPECT_EQ(root.child[1], ChildRef::leaf(2, 1));
    EXPECT_EQ(root.child[2], ChildRef::leaf(3, 1));
    for (int slot = 3; slot < kBvhWidth; ++slot) EXPECT_FALSE(root.used(slot));
}

// A large input's tree is built on several threads; the wide tree made of it must be the one
// made of a single thread's build, node for node, whatever the number of threads.
TEST(Bvh, ParallelBuildMakesTheSingleThreadedTree) {
    Rng rng(29, 0, 0);
    std::vector<Bounds3> boxes;
    for (int i = 0; i < 20000; ++i) {
        const Vec3 p{rng.uniform() * 100, rng.uniform() * 10, rng.uniform()}, size{rng.uniform(), rng.uniform(), rng.uniform()};
        boxes.push_back({p, p + size});
    }
    const BinaryTree single = build_sah_tree(boxes, {.parallel_from = UINT32_MAX});
    const std::vector<BvhNode> wide = collapse_to_wide(single.nodes);
    for (unsigned threads : {1u, 2u, 7u}) {
        const BinaryTree parallel = build_sah_tree(boxes, {.parallel_from = 1000, .threads = threads});
        EXPECT_NE(parallel.nodes.size(), 0u);
        EXPECT_EQ(parallel.order, single.order) << threads << " threads";
        const std::vector<BvhNode> parallel_wide = collapse_to_wide(parallel.nodes);
        ASSERT_EQ(parallel_wide.size(), wide.size()) << threads << " threads";
        EXPECT_EQ(std::memcmp(parallel_wide.data(), wide.data(), wide.size() * sizeof(BvhNode)), 0) << threads << " threads";
    }
}

TEST(Bvh, CoincidentPrimitivesStillBuildAShallowTree) {
    // 10,000 copies of one triangle: SAH finds no split, the median fallback must bound depth.
    const std::vector<Triangle> same(10000, Triangle{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}});
    const Geometry g({}, same);
    Hit hit;
    EXPECT_TRUE(g.intersect(Ray{{0.2, 0.2, 1}, {0, 0, -1}}, kNoPrimitive, hit));
    EXPECT_EQ(hit.t, 1);
}

TEST(Bvh, BoxesReachingInfinityStillBuild) {
    // Beyond float's range a box rounds out to infinity: from -inf to +inf its centre is NaN,
    // from a finite value to +inf it is infinite. Binning such centres once wrote outside the
    // bins (the sanitizer build catches it); the tree must still hold every primitive once.
    std::vector<Bounds3> boxes;
    for (int i = 0; i < 3000; ++i) {
        const double x = i % 3 == 0 ? -1e300 : i, far = i % 2 == 0 ? 1e300 : i + 0.5;
        boxes.push_back({{x, 0, double(i % 7)}, {far, 1, i % 5 == 0 ? 2e300 : 8}});
    }
    const Bvh bvh = Bvh::build(boxes);
    std::vector<int> seen(bvh.tree_size(), 0);
    bvh.for_each_leaf([&](uint32_t first, uint32_t count) {
        for (uint32_t k = first; k < first + count; ++k) ++seen[k];
    });
    EXPECT_EQ(bvh.tree_size(), boxes.size());
    for (int count : seen) EXPECT_EQ(count, 1);
}

}  // namespace
}  // namespace glint

namespace glint {
namespace {

TEST(Bvh, AutomaticChoiceBuildsATreeOnlyForScenesLargerThanSixteenPrimitives) {
    const RandomScene small = random_scene(16, 16, 0), large = random_scene(16, 9, 8);
    EXPECT_EQ(Geometry(small.spheres, small.triangles).accelerator(), Accelerator::list);
    EXPECT_TRUE(Geometry(small.spheres, small.triangles).sphere_bvh().nodes().empty());
    EXPECT_EQ(Geometry(large.spheres, large.triangles).accelerator(), Accelerator::bvh);
}

}  // namespace
}  // namespace glint
