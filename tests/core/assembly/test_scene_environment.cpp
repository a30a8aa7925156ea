// Scenes lit from far away. An environment: the loader reads `environment` with the rules of
// every scene file, a white furnace returns the environment's radiance everywhere whatever the
// rotation, `visible: false` shows camera rays the film's background. A sun: a facing diffuse
// plane returns irradiance·albedo/π, the disc seen directly has irradiance/(π sin²α). Point and
// spot lights: the inverse-square law and glTF's cone falloff.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "assembly/fingerprint.h"
#include "assembly/scene_loader.h"
#include "support/image_files.h"
#include "support/scene_folder.h"
#include "support/test_support.h"

namespace glint {
namespace {


class SceneEnvironment : public testing::SceneFolderTest {
protected:
    SceneEnvironment() : SceneFolderTest("glint-scene-environment") {
        folder_.write("grey.exr", testing::exr(8, 4, {"Y"}, {std::vector<float>(32, 0.8f)}));
    }
    // A white diffuse sphere filling most of a 16×16 image under the environment `environment`.
    Image furnace(const std::string& environment, const std::string& film = "") const {
        const LoadedScene s = load(R"({"camera": {"position": [0, 0, 3], "look_at": [0, 0, 0], "fov": 45},
            "film": {"width": 16, "height": 16, "spp": 64, "seed": 3)" + film + R"(},
            "environment": )" + environment + R"(,
            "objects": [{"type": "sphere", "center": [0, 0, 0], "radius": 1, "material": {"albedo": 1}}]})");
        return testing::render(s)->film().mean();
    }
};

// Radiance L all round a white diffuse sphere: every bounce returns L, so every pixel is L.
TEST_F(SceneEnvironment, AWhiteFurnaceReturnsTheEnvironmentsRadianceWhateverTheRotation) {
    for (const char* rotation : {"0", "37", "-200"}) {
        const Image image = furnace(R"({"file": "grey.exr", "rotation": )" + std::string(rotation) + "}");
        double sum = 0;
        for (int y = 0; y < 16; ++y)
            for (int x = 0; x < 16; ++x) {
                const Rgb p = image.at(x, y);
                EXPECT_NEAR(p.y, 0.8, 0.08) << x << ", " << y << " at rotation " << rotation;
                sum += p.y;
            }
        EXPECT_NEAR(sum / 256, 0.8, 0.004) << "rotation " << rotation;
    }
}

// Not visible: the corners, which see past the sphere, show the background; the sphere is
// still lit by the environment.
TEST_F(SceneEnvironment, AnInvisibleEnvironmentShowsCameraRaysTheBackground) {
    const Image image = furnace(R"({"file": "grey.exr", "visible": false})", R"(, "background": 0.25)");
    EXPECT_NEAR(image.at(0, 0).y, 0.25, 1e-6);
    EXPECT_NEAR(image.at(15, 15).y, 0.25, 1e-6);
    EXPECT_NEAR(image.at(8, 8).y, 0.8, 0.08);
}

TEST_F(SceneEnvironment, StrengthScalesTheLight) {
    const Image image = furnace(R"({"file": "grey.exr", "strength": 0.5})");
    EXPECT_NEAR(image.at(0, 0).y, 0.4, 1e-6);
    EXPECT_NEAR(image.at(8, 8).y, 0.4, 0.04);
}

TEST_F(SceneEnvironment, BadEnvironmentsGetOneClearError) {
    const auto scene = [](const std::string& environment) { return R"({"environment": )" + environment + "}"; };
    EXPECT_NE(error_of(scene(R"({"strength": 2})")).find("environment: needs a \"file\""), std::string::npos);
    EXPECT_NE(error_of(scene(R"({"file": "grey.exr", "blur": 2})")).find("environment.blur"), std::string::npos);
    EXPECT_NE(error_of(scene(R"({"file": "missing.exr"})")).find("environment.file"), std::string::npos);
    EXPECT_NE(error_of(scene(R"({"file": "../grey.exr"})")).find("inside the scene's folder"), std::string::npos);
    EXPECT_NE(error_of(scene(R"({"file": "grey.exr", "strength": -1})")).find("environment.strength"), std::string::npos);
    EXPECT_NE(error_of(scene(R"({"file": "grey.exr", "visible": 1})")).find("environment.visible"), std::string::npos);
    folder_.write("nan.exr", testing::exr(2, 1, {"Y"}, {{1.0f, std::numeric_limits<float>::quiet_NaN()}}));
    const std::string nan = error_of(scene(R"({"file": "nan.exr"})"));
    EXPECT_NE(nan.find("nan.exr"), std::string::npos) << nan;
}

TEST_F(SceneEnvironment, NegativeTexelsAreZeroWithAWarningThatCountsThem) {
    folder_.write("negative.exr", testing::exr(2, 1, {"Y"}, {{-0.5f, 1.0f}}));
    const LoadedScene s = load(R"({"environment": {"file": "negative.exr"}})");
    ASSERT_EQ(s.warnings.size(), 1u);
    EXPECT_NE(s.warnings[0].find("1 negative values in negative.exr set to 0"), std::string::npos) << s.warnings[0];
    EXPECT_EQ(s.scene->environment()->radiance({0, 0, -1}).y, 0);    // texel 0's centre, u = 1/4
    EXPECT_EQ(s.scene->environment()->radiance({-1, 0, 0}).y, 0.5);  // u = 0, the seam: between 0 and 1
}

// A film of one environment must not resume or merge with another's.
TEST_F(SceneEnvironment, TheFingerprintCoversTheEnvironment) {
    folder_.write("brighter.exr", testing::exr(8, 4, {"Y"}, {std::vector<float>(32, 0.9f)}));
    const auto print = [&](const std::string& environment) {
        const LoadedScene s = load(R"({"environment": )" + environment + "}");
        return fingerprint(*s.scene, s.settings);
    };
    const uint64_t base = print(R"({"file": "grey.exr"})");
    EXPECT_EQ(print(R"({"file": "grey.exr", "rotation": 0, "strength": 1})"), base);
    for (const char* other : {R"({"file": "brighter.exr"})", R"({"file": "grey.exr", "rotation": 10})",
                              R"({"file": "grey.exr", "strength": 2})", R"({"file": "grey.exr", "visible": false})"})
        EXPECT_NE(print(other), base) << other;
    const LoadedScene none = load("{}");
    EXPECT_NE(fingerprint(*none.scene, none.settings), base);
}

// The loader's message for a scene that names no files, or "no error".
std::string error_in(const std::string& text) {
    try {
        parse_scene(text, "");
    } catch (const SceneError& e) {
        return e.what();
    }
    return "no error";
}

// A diffuse plane of albedo 0.6 facing the sun, seen from above, nothing else in the scene.
Image sunlit_plane(const std::string& sun, int spp) {
    const LoadedScene s = parse_scene(R"({"camera": {"position": [0, 5, 0], "look_at": [0, 0, 0], "up": [0, 0, -1], "fov": 20},
        "film": {"width": 8, "height": 8, "spp": )" + std::to_string(spp) + R"(}, "sun": )" + sun + R"(,
        "objects": [{"type": "mesh", "vertices": [[-50, 0, -50], [50, 0, -50], [50, 0, 50], [-50, 0, 50]],
                     "indices": [[0, 2, 1], [0, 3, 2]], "material": {"albedo": 0.6}}]})", "");
    return testing::render(s)->film().mean();
}

TEST(SceneSun, AFacingDiffusePlaneReturnsIrradianceTimesAlbedoOverPi) {
    // A delta sun: every sample is the exact value.
    const Image delta = sunlit_plane(R"({"direction": [0, 1, 0], "irradiance": [3, 2, 1], "angle": 0})", 4);
    for (int y = 0; y < 8; ++y)
        for (int x = 0; x < 8; ++x) {
            const Rgb p = delta.at(x, y);
            EXPECT_NEAR(p.x, 3 * 0.6 / kPi, 1e-6);
            EXPECT_NEAR(p.z, 1 * 0.6 / kPi, 1e-6);
        }
    // A disc of 60°: irradiance is what the facing plane receives, ∫ L cos θ dω = L·π·sin²α,
    // not L times the disc's solid angle (6.7% more at this size).
    const Image disc = sunlit_plane(R"({"direction": [0, 1, 0], "irradiance": 2, "angle": 60})", 64);
    double sum = 0;
    for (float v : disc.rgb) sum += v;
    EXPECT_NEAR(sum / double(disc.rgb.size()), 2 * 0.6 / kPi, 0.005 * 2 * 0.6 / kPi);
    // Tilted by 60°, the plane receives half.
    const Image tilted = sunlit_plane(R"({"direction": [0.8660254037844386, 0.5, 0], "irradiance": 2, "angle": 0})", 4);
    EXPECT_NEAR(tilted.at(3, 3).y, 0.5 * 2 * 0.6 / kPi, 1e-6);
}

// Looking straight at a 10° sun: its disc's radiance is irradiance / (π sin² 5°).
TEST(SceneSun, TheDiscSeenDirectlyHasItsRadiance) {
    const LoadedScene s = parse_scene(R"({"camera": {"position": [0, 0, 0], "direction": [0, 0, -1], "fov": 2},
        "film": {"width": 4, "height": 4, "spp": 4}, "sun": {"direction": [0, 0, -1], "irradiance": 2, "angle": 10}})", "");
    const Image image = testing::render(s)->film().mean();
    const double sin5 = std::sin(5 * kPi / 180);
    EXPECT_NEAR(image.at(1, 1).y, 2 / (kPi * sin5 * sin5), 1e-6 * 2 / (kPi * sin5 * sin5));
}

TEST(SceneSun, BadSunsGetOneClearError) {
    const auto error_of = [](const std::string& sun) { return error_in(R"({"sun": )" + sun + "}"); };
    EXPECT_NE(error_of(R"({"irradiance": 2})").find("sun: needs a \"direction\""), std::string::npos);
    EXPECT_NE(error_of(R"({"direction": [0, 0, 0]})").find("sun.direction: must not be zero"), std::string::npos);
    EXPECT_NE(error_of(R"({"direction": [0, 1, 0], "angle": 180})").find("sun.angle"), std::string::npos);
    EXPECT_NE(error_of(R"({"direction": [0, 1, 0], "size": 1})").find("sun.size"), std::string::npos);
    EXPECT_NE(error_of(R"({"direction": [0, 1, 0], "irradiance": -1})").find("sun.irradiance"), std::string::npos);
}

// A diffuse plane of albedo 0.6 at y = 0 under `light` (nothing else in the scene), seen by a
// narrow camera looking down at the point (x, 0, 0): that point's radiance.
double lit_by(const std::string& light, double x) {
    const LoadedScene s = parse_scene(R"({"camera": {"position": [)" + std::to_string(x) + R"(, 1, 0], "direction": [0, -1, 0], "up": [0, 0, -1], "fov": 0.01},
        "film": {"width": 1, "height": 1, "spp": 4}, "objects": [)" + light + R"(,
        {"type": "mesh", "vertices": [[-50, 0, -50], [50, 0, -50], [50, 0, 50], [-50, 0, 50]],
         "indices": [[0, 2, 1], [0, 3, 2]], "material": {"albedo": 0.6}}]})", "");
    return testing::render(s)->film().mean().at(0, 0).y;
}

TEST(ScenePointLights, APointLightFallsOffAsTheInverseSquare) {
    // Bright enough that no shadow ray is left to roulette (integrator.h): every sample exact.
    const std::string light = R"({"type": "point_light", "position": [0, 2, 0], "intensity": 50})";
    EXPECT_NEAR(lit_by(light, 0), 0.6 / kPi * 50 / 4, 1e-5);
    // At x = 2: distance² 8, cos θ at the plane 2/√8.
    EXPECT_NEAR(lit_by(light, 2), 0.6 / kPi * 50 / 8 * (2 / std::sqrt(8.0)), 1e-5);
}

// A spot pointing down, full to 30° and dark beyond 45° off its axis: glTF's falloff between.
TEST(ScenePointLights, ASpotLightHasGltfsConeFalloff) {
    const std::string spot = R"({"type": "spot_light", "position": [0, 2, 0], "intensity": 50, "direction": [0, -1, 0],
        "inner_angle": 30, "outer_angle": 45})";
    const auto at_angle = [&](double degrees) { return lit_by(spot, 2 * std::tan(degrees * kPi / 180)); };
    const auto point = [&](double degrees) {
        const double c = std::cos(degrees * kPi / 180);
        return 0.6 / kPi * 50 * c * c * c / 4;  // I·cos θ / d², d = 2 / cos θ
    };
    EXPECT_NEAR(at_angle(0), point(0), 1e-5);
    EXPECT_NEAR(at_angle(20), point(20), 1e-5);
    const double c30 = std::cos(kPi / 6), c45 = std::cos(kPi / 4), c40 = std::cos(40 * kPi / 180);
    const double t = (c40 - c45) / (c30 - c45);
    EXPECT_NEAR(at_angle(40), point(40) * t * t, 1e-5);
    EXPECT_EQ(at_angle(50), 0);
}

TEST(ScenePointLights, BadPointLightsGetOneClearError) {
    const auto error_of = [](const std::string& light) { return error_in(R"({"objects": [)" + light + "]}"); };
    EXPECT_NE(error_of(R"({"type": "point_light"})").find("objects[0]: needs a \"position\""), std::string::npos);
    EXPECT_NE(error_of(R"({"type": "point_light", "position": [0, 1, 0], "radius": 1})").find("objects[0].radius"),
              std::string::npos);
    EXPECT_NE(error_of(R"({"type": "spot_light", "position": [0, 1, 0], "inner_angle": 50, "outer_angle": 40})")
                  .find("objects[0].inner_angle: must be less than outer_angle"),
              std::string::npos);
    EXPECT_NE(error_of(R"({"type": "spot_light", "position": [0, 1, 0], "direction": [0, 0, 0]})")
                  .find("objects[0].direction: must not be zero"),
              std::string::npos);
}

}  // namespace
}  // namespace glint
