// Watertightness: rays from inside closed meshes, aimed exactly at shared edges and vertices,
// must never escape; and the triangle test itself on hard cases.
#include <gtest/gtest.h>

#include <array>
#include <map>
#include <string>

#include "scene/geometry.h"
#include "base/rng.h"

namespace glint {
namespace {

struct Mesh {
    std::vector<Vec3> vertices;
    std::vector<std::array<uint32_t, 3>> faces;

    std::vector<Triangle> triangles(const Vec3& offset) const {
        std::vector<Triangle> out;
        for (const auto& f : faces) out.push_back({vertices[f[0]] + offset, vertices[f[1]] + offset, vertices[f[2]] + offset});
        return out;
    }
};

Mesh cube() {
    Mesh m;
    for (int i = 0; i < 8; ++i) m.vertices.push_back({i & 1 ? 1.0 : -1.0, i & 2 ? 1.0 : -1.0, i & 4 ? 1.0 : -1.0});
    const std::array<std::array<uint32_t, 4>, 6> quads = {{{0, 1, 3, 2}, {4, 6, 7, 5}, {0, 4, 5, 1},
                                                          {2, 3, 7, 6}, {0, 2, 6, 4}, {1, 5, 7, 3}}};
    for (const auto& q : quads) {
        m.faces.push_back({q[0], q[1], q[2]});
        m.faces.push_back({q[0], q[2], q[3]});
    }
    return m;
}

// An icosahedron subdivided `levels` times with vertices shared between faces (as a closed
// indexed mesh has them), pushed onto the unit sphere.
Mesh icosphere(int levels) {
    const double g = (1 + std::sqrt(5.0)) / 2;
    Mesh m;
    for (const Vec3& v : {Vec3{-1, g, 0}, {1, g, 0}, {-1, -g, 0}, {1, -g, 0}, {0, -1, g}, {0, 1, g}, {0, -1, -g},
                          {0, 1, -g}, {g, 0, -1}, {g, 0, 1}, {-g, 0, -1}, {-g, 0, 1}})
        m.vertices.push_back(normalize(v));
    m.faces = {{0, 11, 5}, {0, 5, 1},  {0, 1, 7},   {0, 7, 10}, {0, 10, 11}, {1, 5, 9}, {5, 11, 4},
               {11, 10, 2}, {10, 7, 6}, {7, 1, 8},  {3, 9, 4},  {3, 4, 2},   {3, 2, 6}, {3, 6, 8},
               {3, 8, 9},  {4, 9, 5},  {2, 4, 11},  {6, 2, 10}, {8, 6, 7},   {9, 8, 1}};
    for (int level = 0; level < levels; ++level) {
        std::map<std::pair<uint32_t, uint32_t>, uint32_t> midpoints;
        auto midpoint = [&](uint32_t a, uint32_t b) {
            const auto key = std::minmax(a, b);
            const auto [it, inserted] = midpoints.try_emplace(key, uint32_t(m.vertices.size()));
            if (inserted) m.vertices.push_back(normalize(m.vertices[a] + m.vertices[b]));
            return it->second;
        };
        std::vector<std::array<uint32_t, 3>> faces;
        for (const auto& f : m.faces) {
            const uint32_t ab = midpoint(f[0], f[1]), bc = midpoint(f[1], f[2]), ca = midpoint(f[2], f[0]);
            faces.insert(faces.end(), {{f[0], ab, ca}, {f[1], bc, ab}, {f[2], ca, bc}, {ab, bc, ca}});
        }
        m.faces = faces;
    }
    return m;
}

// Shoots from `origin` at every vertex, every edge midpoint and points along every edge;
// returns how many rays found no triangle.
int escapes(const Mesh& mesh, const Vec3& offset, const Vec3& origin, Accelerator accelerator) {
    const Geometry geometry({}, mesh.triangles(offset), accelerator);
    std::vector<Vec3> targets = mesh.vertices;
    for (const auto& f : mesh.faces)
        for (int e = 0; e < 3; ++e)
            for (double s : {0.5, 0.25, 1.0 / 3, 0.9})
                targets.push_back(mesh.vertices[f[e]] * (1 - s) + mesh.vertices[f[(e + 1) % 3]] * s);
    int missed = 0;
    for (const Vec3& target : targets) {
        const Ray ray{origin + offset, normalize(target - origin)};
        Hit hit;
        missed += !geometry.intersect(ray, kNoPrimitive, hit);
    }
    return missed;
}

TEST(Triangle, ClosedMeshesShotAtSharedEdgesAndVerticesNeverLeakRays) {
    Rng rng(7, 0, 0);
    for (const Mesh& mesh : {cube(), icosphere(3)}) {
        for (const Vec3& offset : {Vec3{0, 0, 0}, Vec3{1e4, -1e4, 1e4}}) {
            for (int trial = 0; trial < 20; ++trial) {
                // The centre (axis-aligned and diagonal directions) and random interior points.
                const Vec3 origin = trial == 0 ? Vec3{0, 0, 0}
                                               : Vec3{rng.uniform() - 0.5, rng.uniform() - 0.5, rng.uniform() - 0.5} * 0.8;
                EXPECT_EQ(escapes(mesh, offset, origin, Accelerator::bvh), 0) << "offset " << offset.x << " trial " << trial;
                EXPECT_EQ(escapes(mesh, offset, origin, Accelerator::list), 0) << "offset " << offset.x << " trial " << trial;
            }
        }
    }
}

TEST(Triangle, AxisParallelRaysWithSignedZerosHitCubeEdges) {
    const Geometry geometry({}, cube().triangles({}), Accelerator::bvh);
    for (double zero : {0.0, -0.0})
        for (const Vec3& d : {Vec3{1, zero, zero}, Vec3{zero, -1, zero}, Vec3{zero, zero, 1}, normalize(Vec3{1, 1, zero}),
                              normalize(Vec3{-1, zero, -1})}) {
            Hit hit;
            ASSERT_TRUE(geometry.intersect(Ray{{0, 0, 0}, d}, kNoPrimitive, hit));
            EXPECT_TRUE(std::isfinite(hit.t));
            EXPECT_NEAR(hit.t, 1.0 / max_component(abs(d)), 1e-12);  // the cube is [-1, 1]^3
        }
}

TEST(Triangle, RejectsDegenerateAndCoplanarCases) {
    TriangleHit hit;
    const Triangle sliver{{0, 0, 0}, {1, 0, 0}, {2, 0, 0}};          // zero area, collinear
    const Triangle point{{1, 1, 1}, {1, 1, 1}, {1, 1, 1}};           // coincident vertices
    const Triangle flat{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
    EXPECT_FALSE(sliver.intersect(Ray{{0.5, 0, -1}, {0, 0, 1}}, hit));
    EXPECT_FALSE(point.intersect(Ray{{1, 1, 0}, {0, 0, 1}}, hit));
    EXPECT_FALSE(flat.intersect(Ray{{-1, 0.25, 0}, {1, 0, 0}}, hit));  // in the triangle's plane
    EXPECT_TRUE(flat.intersect(Ray{{0.25, 0.25, 1}, {0, 0, -1}}, hit));  // two-sided: from +z
    EXPECT_TRUE(flat.intersect(Ray{{0.25, 0.25, -1}, {0, 0, 1}}, hit));  // and from -z
    EXPECT_DOUBLE_EQ(hit.t, 1);
    EXPECT_NEAR(hit.b0 + hit.b1 + hit.b2, 1, 1e-15);
}

TEST(Triangle, HitPointsStayWithinTheirErrorBounds) {
    Rng rng(8, 0, 0);
    const Triangle t{{1e4, 1e4, 1e4}, {1e4 + 1, 1e4, 1e4 + 0.3}, {1e4, 1e4 + 1, 1e4 - 0.2}};
    for (int i = 0; i < 10000; ++i) {
        const double b1 = rng.uniform() * 0.5, b2 = rng.uniform() * 0.5;
        const Vec3 target = t.v0 * (1 - b1 - b2) + t.v1 * b1 + t.v2 * b2;
        const Ray ray{target + Vec3{3, -2, 5}, normalize(Vec3{-3, 2, -5})};
        TriangleHit hit;
        ASSERT_TRUE(t.intersect(ray, hit));
        const SurfaceInteraction si = t.interaction(hit, 0);
        // The computed point is within p_error of the exact plane point (checked in long double).
        const long double lb1 = hit.b1, lb2 = hit.b2, lb0 = hit.b0;
        for (int a = 0; a < 3; ++a) {
            const long double exact = lb0 * t.v0[a] + lb1 * t.v1[a] + lb2 * t.v2[a];
            EXPECT_LE(std::fabs((long double)si.p[a] - exact), (long double)si.p_error[a]);
        }
    }
}

// The scalar tests of a run's triangles in turn, each hit shrinking the limit: the index of the
// hit kept (-1 for none) and its TriangleHit.
int scalar_in_turn(const std::vector<PackedTriangle>& packed, unsigned skip, const Ray& ray, TriangleHit& kept) {
    const RayShear shear(ray);
    Ray r = ray;
    int expected = -1;
    TriangleHit hit;
    for (uint32_t i = 0; i < packed.size(); ++i)
        if (!(skip >> i & 1) && packed[i].intersect(r, shear, hit)) {
            expected = int(i);
            kept = hit;
            r.tmax = hit.t;
        }
    return expected;
}

// Whether RunTest's closest and any-hit answers for the run are the scalar tests' in turn, bit
// for bit; returns the index of the triangle hit, or -1, with its TriangleHit in `expected_hit`.
int expect_run_as_scalar(const std::vector<float>& run, const std::vector<PackedTriangle>& packed, unsigned skip,
                         const Ray& ray, const std::string& where, TriangleHit& expected_hit) {
    TriangleHit got;
    const int expected = scalar_in_turn(packed, skip, ray, expected_hit);
    const RayShear shear(ray);
    const RunTest test(shear);
    const auto n = static_cast<uint32_t>(packed.size());
    EXPECT_EQ(test.closest(run.data(), n, skip, ray, got), expected) << where;
    EXPECT_EQ(test.any(run.data(), n, skip, ray), expected >= 0) << where;
    if (expected >= 0) {
        EXPECT_EQ(got.t, expected_hit.t) << where;
        EXPECT_EQ(got.b0, expected_hit.b0) << where;
        EXPECT_EQ(got.b1, expected_hit.b1) << where;
        EXPECT_EQ(got.b2, expected_hit.b2) << where;
    }
    return expected;
}

// The run test answers as the scalar test of each triangle in turn does: for runs of 1 to 4
// triangles and rays aimed at random points, at a shared edge and at vertices (from far away
// too, so that the edge functions are tiny against the coordinates), the same triangle, t and
// barycentrics bit for bit, the nearest and the last of equals, with a skipped lane left out.
// The limits are tried where a comparison off by one unit in the last place would show: tmax at
// the hit's t and one unit either side of it, tmin at it and one unit below, and the ray turned
// round, so that the triangles lie behind it, with tmin 0 and -inf.
TEST(Triangle, RunTestAnswersAsTheScalarTestInTurn) {
    Rng rng(9, 0, 0);
    auto point = [&] { return Vec3{rng.uniform(), rng.uniform(), rng.uniform()} * 2 - Vec3{1}; };
    int hits = 0, shared_edge_hits = 0, limit_hits = 0, behind_hits = 0;
    for (int trial = 0; trial < 4000; ++trial) {
        const uint32_t n = 1 + trial % 4;
        const Vec3 offset = trial % 2 ? Vec3{1e4, -3e3, 7e3} : Vec3{0, 0, 0};
        std::vector<PackedTriangle> packed;
        const Vec3 shared_a = point(), shared_b = point();  // an edge the first two triangles share
        for (uint32_t i = 0; i < n; ++i) {
            const Triangle t = i < 2 ? Triangle{shared_a + offset, shared_b + offset, point() + offset}
                                     : Triangle{point() + offset, point() + offset, point() + offset};
            packed.push_back(PackedTriangle::pack(t));
        }
        std::vector<float> run(9 * n + triangle_run::kPadding, std::nanf(""));
        for (uint32_t i = 0; i < n; ++i) triangle_run::put(run.data(), n, i, packed[i]);
        // The target: inside a triangle, on the shared edge, or on a vertex, as stored.
        const Triangle aim = packed[rng.uniform() < 0.5 ? 0 : n - 1].unpack();
        const double b1 = rng.uniform(), b2 = rng.uniform() * (1 - b1);
        const int kind = trial % 4;
        const Vec3 target = kind == 0 ? aim.v0 * (1 - b1 - b2) + aim.v1 * b1 + aim.v2 * b2
                            : kind == 1 ? aim.v0 * (1 - b1) + aim.v1 * b1
                            : kind == 2 ? aim.v1
                                        : aim.v0 + (point() * 1e-9);
        const Vec3 origin = target + normalize(point()) * (trial % 5 == 0 ? 1e5 : 3.0);
        const Ray ray{origin, normalize(target - origin), trial % 3 == 0 ? -kInfinity : 0.0, kInfinity};
        const unsigned skip = trial % 7 == 0 ? 1u : 0u;
        const std::string where = "trial " + std::to_string(trial);
        TriangleHit hit, other;
        const int expected = expect_run_as_scalar(run, packed, skip, ray, where, hit);
        for (const double tmin : {0.0, -kInfinity})
            behind_hits += expect_run_as_scalar(run, packed, skip, {ray.o, -ray.d, tmin, kInfinity}, where + ", turned round", other) >= 0;
        if (expected < 0) continue;
        ++hits;
        shared_edge_hits += kind == 1 && expected < 2;
        const double below = std::nextafter(hit.t, -kInfinity), above = std::nextafter(hit.t, kInfinity);
        for (const double tmax : {hit.t, below, above})
            limit_hits += expect_run_as_scalar(run, packed, skip, {ray.o, ray.d, ray.tmin, tmax}, where + ", tmax near the hit", other) >= 0;
        for (const double tmin : {hit.t, below})
            expect_run_as_scalar(run, packed, skip, {ray.o, ray.d, tmin, kInfinity}, where + ", tmin near the hit", other);
    }
    EXPECT_GT(hits, 2000);
    EXPECT_GT(shared_edge_hits, 300);
    // Below the hit's t, another triangle may still be hit; at and above it, this one is.
    EXPECT_GE(limit_hits, 2 * hits);
    // Turned round, only tmin = -inf sees the triangles.
    EXPECT_GT(behind_hits, hits / 2);
}

}  // namespace
}  // namespace glint
