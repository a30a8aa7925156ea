// Light sampling on hard cases: lights subtending 1e-6 and 1e-12 sr, a light nearly touching
// the shading point, and sample/pdf consistency that MIS depends on.
#include <gtest/gtest.h>

#include "assembly/scene_loader.h"
#include "base/sampling.h"
#include "scene/lights.h"

namespace glint {
namespace {

struct OneLight {
    Geometry geometry;
    std::vector<Material> materials;
    std::vector<uint32_t> material_of_prim;
    LightSet lights;

    OneLight(std::vector<Sphere> spheres, std::vector<Triangle> triangles, double radiance)
        : geometry(std::move(spheres), std::move(triangles)),
          materials{Material{MaterialType::diffuse, Rgb{0}, 1.5, Rgb{radiance}}},
          material_of_prim(geometry.primitive_count(), 0),
          lights(geometry, materials, material_of_prim) {}
};

struct Estimate {
    double mean, sigma;
};

// Irradiance at p with normal n by next-event estimation: mean of L·cos/pdf.
Estimate irradiance_by_light_sampling(const OneLight& scene, const Vec3& p, const Vec3& n, int count) {
    Rng rng(21, 0, 0);
    double sum = 0, sum_sq = 0;
    for (int i = 0; i < count; ++i) {
        LightSample ls;
        double value = 0;
        if (scene.lights.sample(p, kNoPrimitive, rng.uniform(), rng.uniform(), ls)) {
            EXPECT_TRUE(std::isfinite(ls.pdf) && ls.pdf > 0);
            value = ls.emission.x * std::max(0.0, dot(ls.wi, n)) / ls.pdf;
        }
        sum += value;
        sum_sq += value * value;
    }
    const double mean = sum / count;
    return {mean, std::sqrt(std::max(0.0, sum_sq / count - mean * mean) / count)};
}

// A quad light of two triangles fed a stratified 16×16 grid of (u1, u2): u1 both picks the
// triangle and places the point, so each triangle gets exactly its half of the strata. A
// separate random pick would hand each a random share (binomial: 128 ± 8).
TEST(LightSet, AStratifiedLightSampleStaysStratifiedOverEveryTriangleOfAQuad) {
    const OneLight quad({}, {{{0, 1, 0}, {1, 1, 0}, {1, 1, 1}}, {{0, 1, 0}, {1, 1, 1}, {0, 1, 1}}}, 1);
    int on_first = 0;
    for (int i = 0; i < 16; ++i)
        for (int j = 0; j < 16; ++j) {
            LightSample ls;
            ASSERT_TRUE(quad.lights.sample({0.5, 0, 0.5}, kNoPrimitive, (i + 0.5) / 16, (j + 0.5) / 16, ls));
            on_first += ls.prim == 0;
        }
    EXPECT_EQ(on_first, 128);
}

// The same by brute force: cosine-weighted directions, π·L times the fraction that hit.
Estimate irradiance_by_brute_force(const OneLight& scene, const Vec3& p, const Vec3& n, int count) {
    Rng rng(22, 0, 0);
    const Frame frame = Frame::around(n);
    int hits = 0;
    for (int i = 0; i < count; ++i) {
        Hit hit;
        hits += scene.geometry.intersect(Ray{p, frame.to_world(sample_cosine_hemisphere(rng.uniform(), rng.uniform()))},
                                         kNoPrimitive, hit);
    }
    const double f = double(hits) / count;
    return {kPi * f, kPi * std::sqrt(f * (1 - f) / count)};
}

TEST(Lights, TinyFarSpheresHaveFinitePdfsAndExactIrradiance) {
    // Solid angles of 1e-6 sr and about 3e-12 sr: in float, 1 - cos θmax would be 0.
    for (const double ratio : {std::sqrt(1e-6 / kPi), 1e-6}) {
        const double distance = 1e3, radius = ratio * distance;
        const OneLight scene({Sphere{{0, 0, distance}, radius}}, {}, 1.0);
        const Estimate e = irradiance_by_light_sampling(scene, {0, 0, 0}, {0, 0, 1}, 100000);
        const double exact = kPi * ratio * ratio;  // L·π·sin²θmax at normal incidence
        EXPECT_NEAR(e.mean, exact, 3 * e.sigma + 1e-9 * exact) << "ratio " << ratio;
        // Every sampled direction really reaches the sphere, at the reported distance.
        Rng rng(23, 0, 0);
        for (int i = 0; i < 1000; ++i) {
            LightSample ls;
            ASSERT_TRUE(scene.lights.sample({0, 0, 0}, kNoPrimitive, rng.uniform(), rng.uniform(), ls));
            Hit hit;
            ASSERT_TRUE(scene.geometry.intersect(Ray{{0, 0, 0}, ls.wi}, kNoPrimitive, hit));
            EXPECT_NEAR(hit.t, ls.distance, 1e-9 * distance);
        }
    }
}

TEST(Lights, NearlyTouchingSphereMatchesBruteForce) {
    const double gap = 1e-6;
    const OneLight scene({Sphere{{0, 0, 1 + gap}, 1}}, {}, 1.0);
    const Estimate nee = irradiance_by_light_sampling(scene, {0, 0, 0}, {0, 0, 1}, 200000);
    const Estimate brute = irradiance_by_brute_force(scene, {0, 0, 0}, {0, 0, 1}, 200000);
    const double exact = kPi / ((1 + gap) * (1 + gap));
    EXPECT_NEAR(nee.mean, brute.mean, 3 * std::hypot(nee.sigma, brute.sigma));
    EXPECT_NEAR(nee.mean, exact, 3 * nee.sigma + 1e-12);
}

TEST(Lights, PdfOfASampledPointEqualsTheSamplesPdf) {
    const Triangle tri{{-1, 2, -1}, {1, 2, -1}, {0, 2.5, 1}};
    const OneLight scene({Sphere{{0, 5, 0}, 1}, Sphere{{3, 0, 0}, 0.5}}, {tri}, 2.0);
    Rng rng(24, 0, 0);
    for (const Vec3& p : {Vec3{0, 0, 0}, Vec3{0, 5, 0.2}}) {  // outside all, and inside the first sphere
        for (int i = 0; i < 3000; ++i) {
            LightSample ls;
            if (!scene.lights.sample(p, kNoPrimitive, rng.uniform(), rng.uniform(), ls)) continue;
            const Ray ray{p, ls.wi, 0, ls.distance * (1 + 1e-9)};
            Hit hit;
            ASSERT_TRUE(scene.geometry.intersect(ray, kNoPrimitive, hit));
            if (hit.prim != ls.prim) continue;  // another light is in front: a different point
            const SurfaceInteraction si = scene.geometry.interaction(ray, hit);
            EXPECT_NEAR(scene.lights.pdf(p, kNoPrimitive, si), ls.pdf, 1e-6 * ls.pdf);
        }
    }
}

TEST(Lights, PickingFollowsPower) {
    // Equal radiance, areas 1 : 4: the larger sphere is picked four times as often.
    const OneLight scene({Sphere{{0, 0, 10}, 1}, Sphere{{0, 0, -10}, 2}}, {}, 1.0);
    Rng rng(25, 0, 0);
    int first = 0;
    const int n = 100000;
    for (int i = 0; i < n; ++i) {
        LightSample ls;
        ASSERT_TRUE(scene.lights.sample({0, 0, 0}, kNoPrimitive, rng.uniform(), rng.uniform(), ls));
        first += ls.prim == 0;
    }
    EXPECT_NEAR(double(first) / n, 0.2, 3 * std::sqrt(0.2 * 0.8 / n));
}

}  // namespace
}  // namespace glint

namespace glint {
namespace {

// smallpt's light: a radius-600 sphere poking 0.27 through a radius-1e5 ceiling sphere.
struct LightThroughCeiling {
    Geometry geometry{{Sphere{{50, 681.33, 81.6}, 600}, Sphere{{50, -99918.4, 81.6}, 1e5}}, {}};
    std::vector<Material> materials{Material{MaterialType::diffuse, Rgb{0}, 1.5, Rgb{12}},
                                    Material{MaterialType::diffuse, Rgb{0.75}, 1.5, Rgb{0}}};
    std::vector<uint32_t> material_of_prim{0, 1};
    LightSet lights{geometry, materials, material_of_prim};
};

// Light arriving at p (on primitive `self`, facing the side `n` points to) from light `light`
// through whatever lies between, by next-event estimation with shadow rays: the mean of L·cos/pdf
// and the fraction of samples that reach the light. Each sample's pdf is checked against the
// one MIS uses for the same point.
struct Direct {
    Estimate estimate;
    double reached;
};
Direct direct_by_light_sampling(const Geometry& geometry, const LightSet& lights, const Vec3& p, const Vec3& n,
                                uint32_t self, uint32_t light, int count) {
    Rng rng(25, 0, 0);
    const Vec3 facing = self == kNoPrimitive ? Vec3{} : n;
    double sum = 0, sum_sq = 0;
    int sampled = 0;
    for (int i = 0; i < count; ++i) {
        LightSample ls;
        double value = 0;
        if (lights.sample(p, self, rng.uniform(), rng.uniform(), ls, facing)) {
            Ray shadow{p, ls.wi, 0, ls.distance};
            if (!geometry.occluded(shadow, self, ls.prim)) {
                ++sampled;
                value = ls.emission.x * std::max(0.0, dot(ls.wi, n)) / ls.pdf;
                Hit hit;
                Ray ray{p, ls.wi, 0, ls.distance * (1 + 1e-9)};
                EXPECT_TRUE(geometry.intersect(ray, self, hit) && hit.prim == light);
                EXPECT_NEAR(lights.pdf(p, self, geometry.interaction(ray, hit), facing), ls.pdf, 1e-6 * ls.pdf)
                    << p.x << " " << p.y << " " << p.z;
            }
        }
        sum += value;
        sum_sq += value * value;
    }
    const double mean = sum / count;
    return {{mean, std::sqrt((sum_sq / count - mean * mean) / count)}, double(sampled) / count};
}

// The same by brute force: cosine-weighted rays from p, π·L times the fraction that reach the light.
Estimate direct_by_brute_force(const Geometry& geometry, const Vec3& p, const Vec3& n, uint32_t self, uint32_t light,
                               double radiance, int count) {
    Rng rng(26, 0, 0);
    const Frame frame = Frame::around(n);
    int hits = 0;
    for (int i = 0; i < count; ++i) {
        Hit hit;
        const Ray ray{p, frame.to_world(sample_cosine_hemisphere(rng.uniform(), rng.uniform()))};
        hits += geometry.intersect(ray, self, hit) && hit.prim == light;
    }
    const double f = double(hits) / count;
    return {radiance * kPi * f, radiance * kPi * std::sqrt(f * (1 - f) / count)};
}

TEST(Lights, LightCutByAnOpaqueSphereIsSampledOnTheVisibleCap) {
    const LightThroughCeiling scene;
    const Vec3 p{50, 0, 81.6}, n{0, 1, 0};
    const Direct nee = direct_by_light_sampling(scene.geometry, scene.lights, p, n, kNoPrimitive, 0, 20000);
    // Nearly every sample lands on the visible disc (the whole cone would find it ~5% of the time).
    EXPECT_GT(nee.reached, 0.9);
    const Estimate brute = direct_by_brute_force(scene.geometry, p, n, kNoPrimitive, 0, 12, 400000);
    EXPECT_NEAR(nee.estimate.mean, brute.mean, 4 * std::hypot(nee.estimate.sigma, brute.sigma));
}

// smallpt's light is cut by five walls; which of their caps holds what a point sees depends on
// the point's side of each wall (LightSet keeps them smallest first and takes the first on that
// side). Inside the box that is the ceiling's hole; above the ceiling and beyond the right wall,
// the part of the light above the ceiling and beyond that wall; on the left wall (its own
// sphere, where the side comes from the normal) the hole again.
TEST(Lights, LightCutBySeveralWallsIsSampledOnTheCapEachPointSees) {
    const LoadedScene loaded = load_scene(GLINT_SCENES_DIR "/cornell.json");
    const Geometry& geometry = loaded.scene->geometry();
    const LightSet& lights = loaded.scene->lights();
    constexpr uint32_t kLeftWall = 0, kLight = 8;
    struct Case {
        Vec3 p, n;
        uint32_t self;
    };
    for (const Case& c : {Case{{50, 40, 81.6}, {0, 1, 0}, kNoPrimitive}, Case{{2, 60, 2}, normalize({1, 1, 1}), kNoPrimitive},
                          Case{{700, 100, 81.6}, normalize({-1, 1, 0}), kNoPrimitive},
                          Case{{1, 60, 81.6}, {1, 0, 0}, kLeftWall}}) {
        const Direct nee = direct_by_light_sampling(geometry, lights, c.p, c.n, c.self, kLight, 20000);
        EXPECT_GT(nee.reached, 0.4) << c.p.x << " " << c.p.y << " " << c.p.z;
        const Estimate brute = direct_by_brute_force(geometry, c.p, c.n, c.self, kLight, 12, 400000);
        EXPECT_NEAR(nee.estimate.mean, brute.mean, 4 * std::hypot(nee.estimate.sigma, brute.sigma))
            << c.p.x << " " << c.p.y << " " << c.p.z;
    }
}

}  // namespace
}  // namespace glint
