// Scenes lit by an environment: the loader reads `environment` with the rules of every scene
// file, a white furnace returns the environment's radiance everywhere whatever the rotation,
// `visible: false` shows camera rays the film's background, and a scene without an environment
// has a black or constant sky as before.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "io/fingerprint.h"
#include "io/scene_loader.h"
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

}  // namespace
}  // namespace glint
