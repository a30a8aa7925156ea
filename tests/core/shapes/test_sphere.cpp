// Spheres on hard cases: smallpt's radius-1e5 walls seen from ~100 units, rays leaving the
// surface, and a second surface a hair away.
#include <gtest/gtest.h>

#include "scene/geometry.h"
#include "base/rng.h"
#include "base/sampling.h"

namespace glint {
namespace {

// smallpt's left wall: the box interior lies outside this sphere, around x = 1.
const Sphere kWall{{1e5 + 1, 40.8, 81.6}, 1e5};

// Exact-as-possible hit distance in long double, for reference.
long double reference_t(const Sphere& s, const Ray& r) {
    const long double fx = (long double)r.o.x - s.centre.x, fy = (long double)r.o.y - s.centre.y,
                      fz = (long double)r.o.z - s.centre.z;
    const long double b = fx * r.d.x + fy * r.d.y + fz * r.d.z;
    const long double c = fx * fx + fy * fy + fz * fz - (long double)s.radius * s.radius;
    const long double a = (long double)r.d.x * r.d.x + (long double)r.d.y * r.d.y + (long double)r.d.z * r.d.z;
    return (-b - std::sqrt(b * b - a * c)) / a;
}

TEST(Sphere, HugeWallHitPointsLieOnTheSurface) {
    Rng rng(1, 0, 0);
    double worst_surface = 0, worst_t = 0;
    for (int i = 0; i < 100000; ++i) {
        // From inside the box, ~50-100 units from the wall, in directions that reach it.
        const Vec3 o{30 + 40 * rng.uniform(), 10 + 60 * rng.uniform(), 20 + 120 * rng.uniform()};
        Vec3 d = sample_uniform_sphere(rng.uniform(), rng.uniform());
        if (d.x > -0.05) d.x = -0.05 - std::fabs(d.x);  // towards x = 1, grazing ones included
        const Ray ray{o, normalize(d)};
        double t;
        ASSERT_TRUE(kWall.intersect(ray, false, t));
        const SurfaceInteraction si = kWall.interaction(ray, t, 0);
        worst_surface = std::max(worst_surface, std::fabs(length(si.p - kWall.centre) - kWall.radius) / kWall.radius);
        worst_t = std::max(worst_t, double(std::fabs((long double)t - reference_t(kWall, ray)) / reference_t(kWall, ray)));
    }
    EXPECT_LT(worst_surface, 1e-4);  // the bound
    EXPECT_LT(worst_surface, 1e-15); // what double with re-projection actually gives
    EXPECT_LT(worst_t, 1e-9);
}

TEST(Sphere, RaysLeavingTheHugeWallNeverHitItAgain) {
    const Geometry geometry({kWall}, {});
    Rng rng(2, 0, 0);
    int self_hits = 0, inward_misses = 0;
    for (int i = 0; i < 1000000; ++i) {
        const Vec3 o{30 + 40 * rng.uniform(), 10 + 60 * rng.uniform(), 20 + 120 * rng.uniform()};
        const Ray primary{o, normalize(Vec3{-1, 2 * rng.uniform() - 1, 2 * rng.uniform() - 1})};
        Hit hit;
        ASSERT_TRUE(geometry.intersect(primary, kNoPrimitive, hit));
        const SurfaceInteraction si = geometry.interaction(primary, hit);
        // Any direction on the side facing the box (the outward normal's side, since the box
        // lies outside the wall's sphere): the path leaves the wall and must not see it again.
        const Frame frame = Frame::around(si.n);
        const Vec3 w = frame.to_world(sample_cosine_hemisphere(rng.uniform(), rng.uniform()));
        Hit again;
        self_hits += geometry.intersect(spawn_ray(si, w), si.prim, again);
        // Into the wall, the ray must find the far side (2r·cos θ away), never the surface it left.
        const Vec3 in = -w;
        if (!geometry.intersect(spawn_ray(si, in), si.prim, again) || again.t < 1) ++inward_misses;
    }
    EXPECT_EQ(self_hits, 0);
    EXPECT_EQ(inward_misses, 0);
}

TEST(Sphere, SpawnedRaysStartOnTheRightSideOfSmallAndFarSpheres) {
    Rng rng(3, 0, 0);
    for (double radius : {1e-3, 1.0, 1e5}) {
        for (double distance : {0.0, 1e3, 1e5}) {
            const Sphere s{{distance, -distance, 0.5 * distance}, radius};
            for (int i = 0; i < 2000; ++i) {
                const Vec3 n = sample_uniform_sphere(rng.uniform(), rng.uniform());
                const Ray ray{s.centre + n * (3 * radius), -n};
                double t;
                ASSERT_TRUE(s.intersect(ray, false, t));
                const SurfaceInteraction si = s.interaction(ray, t, 0);
                const Vec3 outside = offset_ray_origin(si, si.n), inside = offset_ray_origin(si, -si.n);
                EXPECT_GT(length(outside - s.centre), radius) << radius << " at " << distance;
                EXPECT_LT(length(inside - s.centre), radius) << radius << " at " << distance;
            }
        }
    }
}

TEST(Sphere, ASecondSurfaceAHairAwayIsStillHit) {
    // Two concentric shells 1e-6 relative apart: a ray leaving the inner one outward must meet
    // the outer one (a fixed epsilon of 1e-4 would skip it).
    const Sphere inner{{0, 0, 0}, 100}, outer{{0, 0, 0}, 100 * (1 + 1e-6)};
    const Geometry geometry({inner, outer}, {});
    Rng rng(4, 0, 0);
    for (int i = 0; i < 10000; ++i) {
        const Vec3 n = sample_uniform_sphere(rng.uniform(), rng.uniform());
        const Ray ray{n * 50, n};
        Hit hit;
        ASSERT_TRUE(geometry.intersect(ray, kNoPrimitive, hit));
        ASSERT_EQ(hit.prim, 0u);
        const SurfaceInteraction si = geometry.interaction(ray, hit);
        ASSERT_TRUE(geometry.intersect(spawn_ray(si, n), si.prim, hit));
        EXPECT_EQ(hit.prim, 1u);
        EXPECT_NEAR(hit.t, 1e-4, 1e-9);
    }
}

TEST(Sphere, TangentAndMissingRaysReportNoHit) {
    const Sphere s{{0, 0, 0}, 1};
    double t;
    EXPECT_FALSE(s.intersect(Ray{{-5, 1.0000001, 0}, {1, 0, 0}}, false, t));
    EXPECT_FALSE(s.intersect(Ray{{5, 0, 0}, {1, 0, 0}}, false, t));  // pointing away
    EXPECT_TRUE(s.intersect(Ray{{-5, 0.9999999, 0}, {1, 0, 0}}, false, t));
    EXPECT_TRUE(std::isfinite(t));
}

}  // namespace
}  // namespace glint

namespace glint {
namespace {

// The list's four-lane test must answer as a scalar loop over Sphere::intersect does, bit for
// bit: nine spheres (a last group of one) from smallpt's walls to a speck, three of them equal
// (a tie the last must win: indices 3 and 7 share a lane, 4 has another), rays from random
// points, from points on the spheres (leaving them), and along the axes.
TEST(SphereList, AnswersAsTheScalarTestBitForBit) {
    const std::vector<Sphere> spheres{kWall, {{50, 40.8, -1e5 + 170}, 1e5}, {{27, 16.5, 47}, 16.5},
                                      {{73, 16.5, 78}, 16.5}, {{73, 16.5, 78}, 16.5}, {{50, 30, 60}, 1e-3},
                                      {{50, 681.33, 81.6}, 600}, {{73, 16.5, 78}, 16.5}, {{-99901, 40.8, 81.6}, 1e5}};
    const SphereList list(spheres);
    Rng rng(7, 0, 0);
    int hits = 0, self_hits = 0;
    for (int i = 0; i < 20000; ++i) {
        Ray ray;
        uint32_t self = kNoPrimitive;
        ray.o = Vec3(100 * rng.uniform(), 80 * rng.uniform(), 170 * rng.uniform());
        if (i % 3 == 1) {
            self = uint32_t(rng.uniform() * double(spheres.size()));
            const Sphere& s = spheres[self];
            ray.o = s.centre + sample_uniform_sphere(rng.uniform(), rng.uniform()) * s.radius;
        }
        ray.d = i % 3 == 2 ? Vec3(i % 2 ? 1.0 : -1.0, 0, 0) : sample_uniform_sphere(rng.uniform(), rng.uniform());
        if (i % 5 == 0) ray.tmax = 100 * rng.uniform();
        int expected = -1;
        double expected_t = ray.tmax;
        for (uint32_t k = 0; k < spheres.size(); ++k) {
            double t;
            Ray r = ray;
            r.tmax = expected_t;
            if (spheres[k].intersect(r, k == self, t)) expected = int(k), expected_t = t;
        }
        double t = -1;
        const int found = list.closest(ray, self, t);
        ASSERT_EQ(found, expected) << "ray " << i;
        if (found >= 0) {
            ASSERT_EQ(t, expected_t) << "ray " << i;
            hits += 1;
            self_hits += found == int(self);
        }
        // Occlusion, leaving out the first hit: blocked exactly when another sphere is hit.
        bool blocked = false;
        for (uint32_t k = 0; k < spheres.size(); ++k) {
            double tk;
            blocked |= int(k) != found && spheres[k].intersect(ray, k == self, tk);
        }
        ASSERT_EQ(list.any(ray, self, found < 0 ? kNoPrimitive : uint32_t(found)), blocked) << "ray " << i;
    }
    EXPECT_GT(hits, 15000);
    EXPECT_GT(self_hits, 100);  // rays leaving a sphere into it find its far side
}

}  // namespace
}  // namespace glint
