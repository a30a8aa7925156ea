// The integrator against answers known in closed form, and against itself with and without
// light sampling (which must converge to the same image: smallpt's).
// Also the densities of its strategies (strategies.h) against their own samples.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include "assembly/scene_loader.h"
#include "base/files.h"
#include "base/sampling.h"
#include "render/strategies.h"
#include "support/test_support.h"

namespace glint {
namespace {

using testing::pooled;
using testing::render;
using testing::scene_from;

std::string furnace(double albedo, double emission, bool light_sampling) {
    return R"({"camera": {"direction": [0.3, -0.2, -1], "fov": 90},
               "film": {"width": 8, "height": 8, "spp": 256, "filter": "box", "seed": 5},
               "integrator": {"light_sampling": )" +
           std::string(light_sampling ? "true" : "false") + R"(},
               "objects": [{"type": "sphere", "center": [0, 0, 0], "radius": 1,
                            "material": {"albedo": )" +
           std::to_string(albedo) + R"(}, "emission": )" + std::to_string(emission) + "}]}";
}

TEST(Integrator, ClosedDiffuseSphereGivesEmissionOverOneMinusAlbedo) {
    for (bool light_sampling : {false, true})
        for (double albedo : {0.5, 0.9, 0.99}) {
            const auto job = render(scene_from(furnace(albedo, 0.5, light_sampling)));
            const auto e = pooled(job->film(), 0);
            const double expected = 0.5 / (1 - albedo);
            EXPECT_NEAR(e.mean, expected, 3 * e.sigma) << "albedo " << albedo << " light sampling " << light_sampling;
            EXPECT_EQ(job->film().dropped(), 0u);
        }
}

std::string object_in_uniform_light(const std::string& material) {
    return R"({"camera": {"position": [0, 0, 4], "look_at": [0, 0, 0], "fov": 25},
               "film": {"width": 16, "height": 16, "spp": 256, "filter": "box", "background": 1, "seed": 6},
               "objects": [{"type": "sphere", "center": [0, 0, 0], "radius": 1, "material": )" +
           material + "}]}";
}

TEST(Integrator, LosslessObjectsVanishInUniformLight) {
    // Albedo 1 glass, mirror and diffuse each return exactly the environment's radiance.
    for (const char* material : {R"({"type": "glass", "albedo": 1})", R"({"type": "mirror", "albedo": 1})",
                                 R"({"type": "diffuse", "albedo": 1})"}) {
        const auto job = render(scene_from(object_in_uniform_light(material)));
        for (int c = 0; c < 3; ++c) {
            const auto e = pooled(job->film(), c);
            EXPECT_NEAR(e.mean, 1, 3 * e.sigma + 1e-12) << material;
        }
        // The middle of the image is all sphere: check it alone too.
        const auto centre = pooled(job->film(), 1, 5, 5, 11, 11);
        EXPECT_NEAR(centre.mean, 1, 3 * centre.sigma + 1e-12) << material;
    }
}

TEST(Integrator, AbsorbingObjectsOnlyDarken) {
    for (const char* material : {R"({"type": "glass", "albedo": 0.5})", R"({"type": "mirror", "albedo": 0.5})",
                                 R"({"type": "diffuse", "albedo": 0.5})"}) {
        const auto job = render(scene_from(object_in_uniform_light(material)));
        const auto centre = pooled(job->film(), 0, 5, 5, 11, 11);
        EXPECT_LT(centre.mean + 3 * centre.sigma, 1) << material;
    }
}

// Light sampling with MIS (and light tracing of caustics where the scene has them, and the
// direct view split off where it varies), on Sobol' samples, and smallpt's estimator (no light
// sampling, no light tracing, no BVH, no split, independent samples) estimate the same image; compare them
// on blocks of pixels. 4σ per block keeps the chance of a false alarm
// over all blocks small, and the seeds are fixed, so the outcome repeats.
// `plain_spp`, if given, is smallpt's estimator's own sample count, for highlights it finds rarely.
void expect_same_image(nlohmann::json scene, int block, int plain_spp = 0) {
    scene["integrator"] = {{"light_sampling", true}};
    const auto a = render(scene_from(scene.dump()));
    scene["integrator"] = {
        {"light_sampling", false}, {"accelerator", "list"}, {"light_tracing", "off"}, {"direct_view_rays", 0}};
    scene["film"]["seed"] = 99;
    if (plain_spp > 0) scene["film"]["spp"] = plain_spp;
    scene["film"]["sampler"] = "independent";  // smallpt's samples: the Sobol' ones must not bias
    const auto b = render(scene_from(scene.dump()));
    const Film &fa = a->film(), &fb = b->film();
    for (int y = 0; y < fa.height(); y += block)
        for (int x = 0; x < fa.width(); x += block)
            for (int c = 0; c < 3; ++c) {
                const auto ea = pooled(fa, c, x, y, x + block, y + block), eb = pooled(fb, c, x, y, x + block, y + block);
                EXPECT_NEAR(ea.mean, eb.mean, 4 * std::hypot(ea.sigma, eb.sigma)) << "block " << x << "," << y << " c" << c;
            }
}

TEST(Integrator, LightSamplingConvergesToSmallptsImage) {
    nlohmann::json cornell = nlohmann::json::parse(read_file(GLINT_SCENES_DIR "/cornell.json", 1 << 20));
    cornell["film"] = {{"width", 32}, {"height", 24}, {"spp", 512}};
    expect_same_image(cornell, 8);
}

// Every material at a middling roughness beside smallpt's smooth glass ball and a mirror ball
// under a sphere light and a quad light: glossy vertices take light sampling and MIS, while the
// smooth balls keep light tracing and the CasterSampler at the diffuse vertices, whose chains a
// glossy vertex must break. Any weight that does not sum to one shows against smallpt's estimator.
nlohmann::json rough_materials_scene() {
    return nlohmann::json::parse(R"({
        "camera": {"position": [0, 3, 9], "look_at": [0, 0.8, 0], "fov": 40},
        "film": {"width": 24, "height": 16, "spp": 1024},
        "objects": [
          {"type": "mesh", "vertices": [[-6, 0, -6], [6, 0, -6], [6, 0, 6], [-6, 0, 6]],
           "indices": [[0, 2, 1], [0, 3, 2]], "material": {"albedo": 0.7}},
          {"type": "mesh", "vertices": [[-1, 5, -1], [1, 5, -1], [1, 5, 1], [-1, 5, 1]],
           "indices": [[0, 1, 2], [0, 2, 3]], "material": {"albedo": 0}, "emission": 6},
          {"type": "sphere", "center": [4, 5, 2], "radius": 1.2, "material": {"albedo": 0}, "emission": 8},
          {"type": "sphere", "center": [-3, 0.8, 0], "radius": 0.8, "material": {"type": "mirror", "roughness": 0.3}},
          {"type": "sphere", "center": [-1, 0.8, 1], "radius": 0.8,
           "material": {"type": "glass", "roughness": 0.4, "fresnel": "exact"}},
          {"type": "sphere", "center": [1, 0.8, 0], "radius": 0.8, "material": {"type": "plastic", "roughness": 0.25,
           "albedo": [0.8, 0.3, 0.2]}},
          {"type": "sphere", "center": [3, 0.8, 1], "radius": 0.8, "material": {"type": "metal", "roughness": 0.5,
           "albedo": [0.9, 0.7, 0.4]}},
          {"type": "sphere", "center": [0, 0.5, 2.5], "radius": 0.5, "material": {"type": "glass"}},
          {"type": "sphere", "center": [2, 0.4, 3], "radius": 0.4, "material": {"type": "mirror"}},
          {"type": "sphere", "center": [-2.5, 0.4, 3], "radius": 0.4, "material": {"type": "plastic", "albedo": 0.5}}
        ]})");
}

TEST(Integrator, RoughMaterialsMatchPlainPathTracing) {
    const nlohmann::json scene = rough_materials_scene();
    ASSERT_TRUE(Strategies(*scene_from(scene.dump()).scene).light_tracing());
    expect_same_image(scene, 4);
}

TEST(Integrator, GlossyHighlightsMatchPlainPathTracing) {
    // Two lights' highlights on rough metal and plastic floors, the lights out of view: light
    // sampling and BSDF sampling both find them, so MIS weights that do not sum to one show here
    // (halving the BSDF pdf in next-event estimation's weight fails three blocks).
    expect_same_image(nlohmann::json::parse(R"({
        "camera": {"position": [0, 2, 6], "look_at": [0, 0, -1], "fov": 50},
        "film": {"width": 16, "height": 12, "spp": 1024},
        "objects": [
          {"type": "mesh", "vertices": [[-4, 0, -6], [0, 0, -6], [0, 0, 4], [-4, 0, 4]],
           "indices": [[0, 2, 1], [0, 3, 2]], "material": {"type": "metal", "roughness": 0.3, "albedo": 0.9}},
          {"type": "mesh", "vertices": [[0, 0, -6], [4, 0, -6], [4, 0, 4], [0, 0, 4]],
           "indices": [[0, 2, 1], [0, 3, 2]], "material": {"type": "plastic", "roughness": 0.2, "albedo": 0.5}},
          {"type": "mesh", "vertices": [[-1.5, 4, -4], [1.5, 4, -4], [1.5, 4, -3], [-1.5, 4, -3]],
           "indices": [[0, 1, 2], [0, 2, 3]], "material": {"albedo": 0}, "emission": 4},
          {"type": "sphere", "center": [0, 3.6, -1], "radius": 0.3, "material": {"albedo": 0}, "emission": 30}
        ]})"), 4, 16384);
}

TEST(Integrator, RoughnessBelowTheThresholdIsSmoothAndJustAboveItLooksTheSame) {
    // 1e-4 is handled as smooth: the same bytes. 0.035 (α = 1.2e-3) is rough, its normals
    // straying by about 0.07°: the same image within noise, so the switch leaves no seam.
    auto scene = rough_materials_scene();
    scene["film"]["spp"] = 256;
    const auto with_roughness = [&scene](double r) {
        auto s = scene;
        for (auto& object : s["objects"])
            if (object.contains("material") && object["material"].contains("type")) object["material"]["roughness"] = r;
        return render(scene_from(s.dump()));
    };
    const auto smooth = with_roughness(0), tiny = with_roughness(1e-4), rough = with_roughness(0.035);
    for (int y = 0; y < smooth->film().height(); ++y)
        for (int x = 0; x < smooth->film().width(); ++x)
            ASSERT_EQ(smooth->film().pixel(x, y).sum[1], tiny->film().pixel(x, y).sum[1]) << x << "," << y;
    for (int y = 0; y < 16; y += 4)
        for (int x = 0; x < 24; x += 4) {
            const auto a = pooled(smooth->film(), 1, x, y, x + 4, y + 4), b = pooled(rough->film(), 1, x, y, x + 4, y + 4);
            EXPECT_NEAR(a.mean, b.mean, 4 * std::hypot(a.sigma, b.sigma)) << "block " << x << "," << y;
        }
}

TEST(Integrator, NoSampleDroppedAcrossRoughnessAndGrazingAngles) {
    // A sphere in uniform light is seen at every angle up to grazing at its silhouette; a
    // white furnace returns at most what arrives (rough surfaces lose some to single scattering:
    // GGX at roughness 1 keeps about 40%, as its single-scattering albedo says).
    for (const char* type : {"mirror", "glass", "metal", "plastic"})
        for (double r : {1e-4, 0.05, 0.3, 0.7, 1.0}) {
            const std::string material = std::string(R"({"type": ")") + type + R"(", "albedo": 1, "roughness": )" +
                                         std::to_string(r) + "}";
            const auto job = render(scene_from(object_in_uniform_light(material)));
            EXPECT_EQ(job->film().dropped(), 0u) << material;
            const auto e = pooled(job->film(), 1);
            EXPECT_LT(e.mean, 1 + 3 * e.sigma + 1e-12) << material;
            EXPECT_GT(e.mean, 0.3) << material;
        }
}

TEST(Integrator, LightTracedCausticsMatchPlainPathTracing) {
    // A glass and a mirror ball under a small sphere light: the caustics come from light
    // tracing (splats through the tent filter) in one image and from the path tracer in the other.
    nlohmann::json caustic = nlohmann::json::parse(read_file(GLINT_SCENES_DIR "/caustic.json", 1 << 20));
    ASSERT_TRUE(Strategies(*scene_from(caustic.dump()).scene).light_tracing());
    caustic["film"] = {{"width", 24}, {"height", 18}, {"spp", 1024}};
    expect_same_image(caustic, 6);
}

TEST(Integrator, LightTracedMirrorCausticInAnUmbraMatchesPlainPathTracing) {
    // A floor in the umbra of a black ball: its only light comes by way of a mirror ball, so
    // the image is nearly all caustic (camera → diffuse → mirror → light), and a light-tracing
    // splat weight off by 15% shows at more than 4σ over the whole image.
    auto scene = nlohmann::json::parse(R"({
        "camera": {"position": [0, 8, -10], "look_at": [0, 0, 0], "fov": 30},
        "film": {"width": 12, "height": 9, "spp": 2048},
        "objects": [
          {"type": "mesh", "vertices": [[-4, 0, -4], [4, 0, -4], [4, 0, 4], [-4, 0, 4]],
           "indices": [[0, 2, 1], [0, 3, 2]], "material": {"albedo": 0.8}},
          {"type": "sphere", "center": [-6, 7, 0], "radius": 5, "material": {"albedo": 0}},
          {"type": "sphere", "center": [9, 10, 0], "radius": 4, "material": {"type": "mirror", "albedo": 0.9}},
          {"type": "sphere", "center": [-12, 14, 0], "radius": 3, "material": {"albedo": 0}, "emission": 20}
        ]})");
    const auto traced = render(scene_from(scene.dump()));
    ASSERT_TRUE(Strategies(*scene_from(scene.dump()).scene).light_tracing());
    scene["integrator"] = {{"light_sampling", false}, {"light_tracing", "off"}};
    scene["film"]["spp"] = 131072;  // plain path tracing finds the caustic rarely
    const auto plain = render(scene_from(scene.dump()));
    for (int c = 0; c < 3; ++c) {
        const auto a = pooled(traced->film(), c), b = pooled(plain->film(), c);
        EXPECT_NEAR(a.mean, b.mean, 4 * std::hypot(a.sigma, b.sigma)) << "channel " << c;
        EXPECT_LT(std::hypot(a.sigma, b.sigma), 0.035 * b.mean) << "too noisy to see a 15% error";
    }
}

// The same for the sun, of 20° so that plain path tracing finds its disc: a floor of `floor`
// in the umbra of a black ball, lit by way of a mirror ball. Light paths from the sun start
// across the ball's disc, from outside the scene. Green over pixels (2.., 2..), which are nearly
// all caustic (the others see the penumbra too): light traced, and plain path tracing's.
std::pair<testing::Estimate, testing::Estimate> sun_caustic(const nlohmann::json& floor) {
    auto scene = nlohmann::json::parse(R"({
        "camera": {"position": [0, 8, -4], "look_at": [0, 0, 0], "fov": 25},
        "film": {"width": 12, "height": 9, "spp": 16384},
        "sun": {"direction": [-0.3, 0.95, 0], "irradiance": 3, "angle": 20},
        "objects": [
          {"type": "mesh", "vertices": [[-4, 0, -4], [4, 0, -4], [4, 0, 4], [-4, 0, 4]],
           "indices": [[0, 2, 1], [0, 3, 2]]},
          {"type": "sphere", "center": [-3, 8, 0], "radius": 4.5, "material": {"albedo": 0}},
          {"type": "sphere", "center": [4.5, 1.5, 0], "radius": 1.5, "material": {"type": "mirror", "albedo": 0.9}}
        ]})");
    scene["objects"][0]["material"] = floor;
    EXPECT_TRUE(Strategies(*scene_from(scene.dump()).scene).light_tracing());
    const auto traced = render(scene_from(scene.dump()));
    scene["integrator"] = {{"light_sampling", false}, {"light_tracing", "off"}};
    scene["film"]["spp"] = 131072;
    const auto plain = render(scene_from(scene.dump()));
    return {pooled(traced->film(), 1, 2, 2), pooled(plain->film(), 1, 2, 2)};
}

TEST(Integrator, LightTracedSunCausticsMatchPlainPathTracing) {
    // Measured: 0.00323 against 0.00344 (2.5σ); with the sun's light paths 1.3 times too
    // bright, 0.00404 (7σ).
    const auto [a, b] = sun_caustic({{"albedo", 0.8}});
    EXPECT_NEAR(a.mean, b.mean, 4 * std::hypot(a.sigma, b.sigma));
    EXPECT_LT(std::hypot(a.sigma, b.sigma), 0.035 * b.mean) << "too noisy to see a 30% error";
}

TEST(Integrator, LightTracedSunCausticsOnAGlossyFloorMatchPlainPathTracing) {
    // A plastic floor: the light paths end there too, splatted through its BSDF toward the eye.
    // Measured: 0.002815 against 0.002979 (2.5σ; at 65536 and 1048576 spp, 0.002820 against
    // 0.002827).
    const auto [a, b] = sun_caustic({{"type", "plastic"}, {"albedo", 0.8}, {"roughness", 0.4}});
    EXPECT_NEAR(a.mean, b.mean, 4 * std::hypot(a.sigma, b.sigma));
    EXPECT_LT(std::hypot(a.sigma, b.sigma), 0.035 * b.mean) << "too noisy to see a 30% error";
}

TEST(Integrator, CausticsSeenInAMirrorMatchPlainPathTracing) {
    // The floor in the umbra of a black ball, lit only by way of a mirror ball, and seen by the
    // camera only in a mirror quad (a triangle mirror is not a caster): light tracing cannot
    // reach it, so its caustic comes from sampling the mirror ball (CasterSampler) combined
    // with the bounce by MIS. Counting the bounce's finds with weight 1 doubles the image
    // (measured: 0.00496 against 0.00248).
    auto scene = nlohmann::json::parse(R"({
        "camera": {"position": [0, 8, -4], "look_at": [0, 0, -14], "fov": 30},
        "film": {"width": 12, "height": 9, "spp": 8192},
        "objects": [
          {"type": "mesh", "vertices": [[-4, 0, -4], [4, 0, -4], [4, 0, 4], [-4, 0, 4]],
           "indices": [[0, 2, 1], [0, 3, 2]], "material": {"albedo": 0.8}},
          {"type": "mesh", "vertices": [[-2, 3.5, -7], [2, 3.5, -7], [2, 8, -7], [-2, 8, -7]],
           "indices": [[0, 1, 2], [0, 2, 3]], "material": {"type": "mirror", "albedo": 0.9}},
          {"type": "sphere", "center": [-6, 7, 0], "radius": 5, "material": {"albedo": 0}},
          {"type": "sphere", "center": [9, 10, 0], "radius": 4, "material": {"type": "mirror", "albedo": 0.9}},
          {"type": "sphere", "center": [-12, 14, 0], "radius": 3, "material": {"albedo": 0}, "emission": 20}
        ]})");
    ASSERT_FALSE(Strategies(*scene_from(scene.dump()).scene).casters().empty());
    const auto sampled = render(scene_from(scene.dump()));
    scene["integrator"] = {{"light_sampling", false}, {"light_tracing", "off"}};
    scene["film"]["spp"] = 65536;
    const auto plain = render(scene_from(scene.dump()));
    ASSERT_TRUE(Strategies(*scene_from(scene.dump()).scene).casters().empty());
    for (int c = 0; c < 3; ++c) {
        const auto a = pooled(sampled->film(), c), b = pooled(plain->film(), c);
        EXPECT_NEAR(a.mean, b.mean, 4 * std::hypot(a.sigma, b.sigma)) << "channel " << c;
        EXPECT_LT(std::hypot(a.sigma, b.sigma), 0.05 * b.mean) << "too noisy to see a wrong weight";
    }
}

TEST(Integrator, LightPathConnectionsCutTheVarianceOfSmallptsBox) {
    // On smallpt's box the error is paths through the balls that a bounce from a diffuse
    // surface finds by chance; light paths reach them from the light (see light_tracer.h).
    // Measured as the mean squared difference of two renders with different seeds (twice the
    // variance, free of any reference): 2.5x below the path tracer alone at 32x24, 64 spp.
    // Splats of the first light vertex alone (no connections, no later vertices) gave 1.27x.
    // Whether the strategies' weights sum to one is tested where it can be seen: the emitter's
    // density against its samples (Lights.CausticEmitterPdfAgreesWithItsSamples) and the
    // images against the path tracer's (above); the connected paths' share of the mean is too
    // small in scenes cheap enough to test for a wrong weight to show there.
    nlohmann::json cornell = nlohmann::json::parse(read_file(GLINT_SCENES_DIR "/cornell.json", 1 << 20));
    cornell["film"] = {{"width", 32}, {"height", 24}, {"spp", 64}};
    auto variance = [&](const char* light_tracing) {
        cornell["integrator"] = {{"light_tracing", light_tracing}};
        cornell["film"]["seed"] = 1;
        const Image a = render(scene_from(cornell.dump()))->film().mean();
        cornell["film"]["seed"] = 2;
        const Image b = render(scene_from(cornell.dump()))->film().mean();
        return rmse(a, b) * rmse(a, b) / 2;
    };
    EXPECT_LT(variance("auto"), 0.6 * variance("off"));
}

TEST(Integrator, TriangleLightsAndMisMatchPlainPathTracing) {
    // A floor, a two-sided emissive quad above it and a sphere between: triangle light sampling
    // and the MIS weights on both sides of a triangle light.
    const auto scene = nlohmann::json::parse(R"({
        "camera": {"position": [0, 3, 6], "look_at": [0, 0.5, 0], "fov": 50},
        "film": {"width": 24, "height": 24, "spp": 512, "filter": "box"},
        "objects": [
          {"type": "mesh", "vertices": [[-5, 0, -5], [5, 0, -5], [5, 0, 5], [-5, 0, 5]],
           "indices": [[0, 2, 1], [0, 3, 2]], "material": {"albedo": [0.8, 0.6, 0.4]}},
          {"type": "mesh", "vertices": [[-1, 3, -1], [1, 3, -1], [1, 3, 1], [-1, 3, 1]],
           "indices": [[0, 1, 2], [0, 2, 3]], "material": {"albedo": 0.5}, "emission": 4},
          {"type": "sphere", "center": [0.5, 0.8, 0], "radius": 0.8, "material": {"albedo": 0.7}}
        ]})");
    expect_same_image(scene, 6);
}

TEST(Integrator, DegenerateGeometryIsIgnoredAndNeverMakesNaN) {
    // Zero-area and coincident-vertex triangles, some emissive: they are never hit and never
    // become lights (documented in README.md), and the image stays finite.
    const auto job = render(scene_from(R"({
        "camera": {"position": [0, 0, 3], "look_at": [0, 0, 0]},
        "film": {"width": 16, "height": 16, "spp": 16, "background": 0.5},
        "objects": [
          {"type": "mesh", "vertices": [[0, 0, 0], [1, 0, 0], [2, 0, 0], [0, 0, 0]],
           "indices": [[0, 1, 2], [0, 0, 0], [0, 3, 1]], "emission": 10},
          {"type": "sphere", "center": [0, 0, 0], "radius": 0.5}
        ]})"));
    EXPECT_EQ(job->film().dropped(), 0u);
    const Image image = job->film().mean();
    for (float v : image.rgb) ASSERT_TRUE(std::isfinite(v));
    EXPECT_NEAR(pooled(job->film(), 0, 0, 0, 2, 2).mean, 0.5, 1e-12);  // a corner sees only the background
}

TEST(Strategies, CausticEmitterPdfAgreesWithItsSamples) {
    // The path tracer weighs its bounces against light paths by the emitter's density of the
    // light point and direction it reached; the light paths carry cos / that density from
    // sampling. The two must agree for the weights to sum to one.
    const LoadedScene loaded = load_scene(GLINT_SCENES_DIR "/cornell.json");
    const Strategies strategies(*loaded.scene);
    const CausticEmitter& emitter = strategies.caustic_emitter();
    ASSERT_FALSE(emitter.empty());
    Rng rng(31, 0, 0);
    int emitted = 0;
    for (int i = 0; i < 20000; ++i) {
        EmittedRay e;
        if (!emitter.sample(rng.uniform(), rng.uniform(), rng.uniform(), rng.uniform(), rng.uniform(), e)) continue;
        ++emitted;
        const Sphere& light = loaded.scene->geometry().sphere(e.light);
        const double cos_out = dot(normalize(e.ray.o - light.centre), e.ray.d);
        EXPECT_NEAR(emitter.pdf(e.light, e.ray.o, e.ray.d) * e.emitted_ratio, cos_out, 1e-9 * cos_out);
        EXPECT_NEAR(e.weight.x, 12 * e.emitted_ratio, 1e-9 * e.weight.x);
    }
    EXPECT_GT(emitted, 19000);
}

TEST(Strategies, CasterSamplerDensityIntegratesToTheSolidAngleOfItsConesUnion) {
    // Two overlapping cones and one the point is inside of (never picked): the mean of 1/pdf
    // over sample() is the solid angle the union of the other two covers, which uniform
    // directions measure independently. Miscounting the overlap or the choice among casters
    // moves the mean by a third or more.
    const LoadedScene loaded = parse_scene(R"({"objects": [
        {"type": "sphere", "center": [0, 0, 3], "radius": 1, "material": {"type": "mirror"}},
        {"type": "sphere", "center": [0.8, 0, 3.5], "radius": 1.2, "material": {"type": "glass"}},
        {"type": "sphere", "center": [0, 0, 0], "radius": 0.5, "material": {"type": "glass"}},
        {"type": "sphere", "center": [0, 9, 0], "radius": 1, "material": {"albedo": 0}, "emission": 5}]})", {});
    const Strategies strategies(*loaded.scene);
    const CasterSampler& casters = strategies.casters();
    ASSERT_FALSE(casters.empty());
    const Vec3 p{0, 0, 0.2};
    Rng rng(7, 0, 0);
    double sum = 0, union_hits = 0;
    constexpr int kSamples = 200000;
    for (int i = 0; i < kSamples; ++i) {
        Vec3 wi;
        double pdf;
        ASSERT_TRUE(casters.sample(p, rng.uniform(), rng.uniform(), rng.uniform(), wi, pdf));
        EXPECT_NEAR(casters.pdf(p, wi), pdf, 1e-12 * pdf);
        sum += 1 / pdf;
        const Vec3 u = sample_uniform_sphere(rng.uniform(), rng.uniform());
        union_hits += casters.pdf(p, u) > 0;
    }
    const double by_pdf = sum / kSamples, uniform = 4 * kPi * union_hits / kSamples;
    EXPECT_NEAR(by_pdf, uniform, 0.02 * uniform);
    EXPECT_EQ(casters.pdf(Vec3{0, 0, 0.3}, Vec3{0, 0, -1}), 0);  // away from every cone
}

}  // namespace
}  // namespace glint
