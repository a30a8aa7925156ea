// Scenes with UVs, vertex normals and image textures: the loader reads them with the rules of
// mesh files, a material looks its textures up at the interpolated UVs (orientation, bilinear
// weights, wrap, sRGB), and a texture renders the same from PNG and from EXR.
#include <gtest/gtest.h>

#include <cmath>

#include "assembly/scene_loader.h"
#include "support/image_files.h"
#include "support/scene_folder.h"
#include "support/test_support.h"

namespace glint {
namespace {


// A 2×2 RGB texture, rows top first: red, green over blue, white.
const std::vector<uint8_t> kQuadrants = {255, 0, 0, 0, 255, 0, 0, 0, 255, 255, 255, 255};

// A unit quad in z = 0 facing +z, UVs (0, 0) at (-1, -1) to (1, 1) at (1, 1), with `material`.
std::string quad_scene(const std::string& material, const std::string& extra = "") {
    return R"({"objects": [{"type": "mesh", "vertices": [[-1, -1, 0], [1, -1, 0], [1, 1, 0], [-1, 1, 0]],
        "uvs": [[0, 0], [1, 0], [1, 1], [0, 1]], "indices": [[0, 1, 2], [0, 2, 3]], "material": )" +
           material + "}" + extra + "]}";
}

class SceneTextures : public testing::SceneFolderTest {
protected:
    SceneTextures() : SceneFolderTest("glint-scene-textures") {
        folder_.write("quadrants.png", testing::png(2, 2, 3, kQuadrants));
    }
    // The material of the quad at uv, found by a ray through the point with those UVs.
    static Material at_uv(const Scene& scene, double u, double v) {
        const Ray ray{{2 * u - 1, 2 * v - 1, 3}, {0, 0, -1}};
        Hit hit;
        EXPECT_TRUE(scene.geometry().intersect(ray, kNoPrimitive, hit));
        Material scratch;
        return scene.material_at(scene.geometry().interaction(ray, hit), scratch);
    }
};

TEST_F(SceneTextures, AlbedoIsLookedUpAtTheInterpolatedUvsWithVUpward) {
    const LoadedScene s = load(quad_scene(R"({"albedo": {"texture": "quadrants.png"}})"));
    EXPECT_EQ(at_uv(*s.scene, 0.25, 0.25).albedo, (Rgb{0, 0, 1}));  // bottom left: blue
    EXPECT_EQ(at_uv(*s.scene, 0.75, 0.75).albedo, (Rgb{0, 1, 0}));  // top right: green
    EXPECT_EQ(at_uv(*s.scene, 0.25, 0.75).albedo, (Rgb{1, 0, 0}));
    // Halfway between blue and white, and across the wrapped edge the same.
    EXPECT_EQ(at_uv(*s.scene, 0.5, 0.25).albedo, (Rgb{0.5, 0.5, 1}));
    EXPECT_EQ(at_uv(*s.scene, 0.999999, 0.25).albedo.z, 1);
    const Rgb across = at_uv(*s.scene, 0.0000001, 0.25).albedo;
    EXPECT_NEAR(across.x, 0.5, 1e-6);
}

TEST_F(SceneTextures, UvScaleOffsetAndScaleApply) {
    const LoadedScene s = load(quad_scene(
        R"({"albedo": {"texture": "quadrants.png", "uv_scale": [2, 2], "uv_offset": [0.5, 0], "scale": [0.5, 1, 1]}})"));
    // (0.375, 0.125) -> (1.25, 0.25): wrapped to the bottom-left texel's centre.
    EXPECT_EQ(at_uv(*s.scene, 0.375, 0.125).albedo, (Rgb{0, 0, 1}));
    // (0.625, 0.375) -> (1.75, 0.75): the top-right texel (green), its red scaled (by 0.5: still 0).
    EXPECT_EQ(at_uv(*s.scene, 0.625, 0.375).albedo, (Rgb{0, 1, 0}));
    EXPECT_EQ(at_uv(*s.scene, 0.375, 0.375).albedo, (Rgb{0.5, 0, 0}));  // (1.25, 0.75) -> red, halved
}

TEST_F(SceneTextures, ColoursAreDecodedFromSrgbAndNumbersAreLinear) {
    folder_.write("grey.png", testing::png(1, 1, 1, {128}));
    const LoadedScene s = load(quad_scene(
        R"({"type": "plastic", "albedo": {"texture": "grey.png"}, "roughness": {"texture": "grey.png"},
            "metallic": {"texture": "quadrants.png", "channel": "b"}})"));
    const Material m = at_uv(*s.scene, 0.25, 0.25);
    EXPECT_NEAR(m.albedo.x, srgb_to_linear(128), 1e-15);
    EXPECT_NEAR(m.roughness, 128 / 255.0, 1e-15);
    EXPECT_EQ(m.metallic, 1);  // blue's channel b
    EXPECT_EQ(s.scene->textures().size(), 2u);  // grey.png read once for both
    const LoadedScene linear = load(quad_scene(R"({"albedo": {"texture": "grey.png", "colorspace": "linear"}})"));
    EXPECT_NEAR(at_uv(*linear.scene, 0.5, 0.5).albedo.y, 128 / 255.0, 1e-15);
}

TEST_F(SceneTextures, ATextureOfSeveralMaterialsIsLoadedOnce) {
    const std::string tex = R"({"albedo": {"texture": "quadrants.png"}})";
    const LoadedScene s = load(quad_scene(tex, R"(, {"type": "sphere", "center": [0, 0, -5], "radius": 1, "material": )" + tex + "}"));
    EXPECT_EQ(s.scene->textures().size(), 1u);
}

TEST_F(SceneTextures, BadTexturesAreOneErrorNamingTheFileAndThePath) {
    const auto with = [&](const std::string& texture) { return error_of(quad_scene(R"({"albedo": )" + texture + "}")); };
    EXPECT_NE(with(R"({"texture": "missing.png"})").find("objects[0].material.albedo.texture"), std::string::npos);
    EXPECT_NE(with(R"({"texture": "../outside.png"})").find("must stay inside the scene's folder"), std::string::npos);
    folder_.write("broken.png", {0x89, 'P', 'N', 'G', 1, 2, 3});
    EXPECT_NE(with(R"({"texture": "broken.png"})").find("broken.png"), std::string::npos);
    EXPECT_NE(with(R"({"texture": "quadrants.png", "channel": "x"})").find("albedo.channel"), std::string::npos);
    EXPECT_NE(with(R"({"texture": "quadrants.png", "wrap": "clamp"})").find("albedo.wrap: unknown field"), std::string::npos);
    EXPECT_NE(with(R"({"scale": 1})").find("needs a \"texture\""), std::string::npos);
}

TEST_F(SceneTextures, TheScenesTexelsAreBoundedPerFileAndInAll) {
    SceneLimits limits;
    limits.max_texels_per_file = 3;
    const std::string text = quad_scene(R"({"albedo": {"texture": "quadrants.png"}})");
    try {
        parse_scene(text, folder_.path(), limits);
        FAIL();
    } catch (const SceneError& e) {
        EXPECT_NE(std::string(e.what()).find("quadrants.png"), std::string::npos) << e.what();
    }
    limits = {};
    limits.max_texels = 3;
    try {
        parse_scene(text, folder_.path(), limits);
        FAIL();
    } catch (const SceneError& e) {
        EXPECT_NE(std::string(e.what()).find("the scene's textures would hold more than 3 texels"), std::string::npos) << e.what();
    }
}

TEST_F(SceneTextures, UvsAndNormalsGiveOnePerVertex) {
    const std::string bad = R"({"objects": [{"type": "mesh", "vertices": [[0, 0, 0], [1, 0, 0], [0, 1, 0]],
        "indices": [[0, 1, 2]], "uvs": [[0, 0], [1, 0]]}]})";
    EXPECT_NE(error_of(bad).find("objects[0].uvs: must be an array of one [u, v] per vertex (3)"), std::string::npos) << error_of(bad);
    const std::string normals = R"({"objects": [{"type": "mesh", "vertices": [[0, 0, 0], [1, 0, 0], [0, 1, 0]],
        "indices": [[0, 1, 2]], "normals": [[0, 0, 1], [0, 0, 1], [0, 1]]}]})";
    EXPECT_NE(error_of(normals).find("objects[0].normals[2]: must be an array of 3 numbers"), std::string::npos);
}

TEST_F(SceneTextures, CutOutsBelongToMeshesThatDoNotEmit) {
    folder_.write("mask.png", testing::png(1, 1, 2, {255, 0}));
    EXPECT_NE(error_of(R"({"objects": [{"type": "sphere", "center": [0, 0, 0], "radius": 1,
        "material": {"alpha": {"texture": "mask.png"}}}]})").find("objects[0].material.alpha: cut-outs apply to meshes only"),
              std::string::npos);
    EXPECT_NE(error_of(quad_scene(R"({"alpha": {"texture": "mask.png"}}, "emission": 1)")).find("cannot have cut-outs"),
              std::string::npos);
}

// A black and white checker renders to the same bytes from PNG and from an EXR of its values.
TEST_F(SceneTextures, ATextureRendersTheSameFromPngAndFromExr) {
    const std::vector<uint8_t> bytes = {0, 255, 255, 0, 255, 0, 0, 255, 0};
    std::vector<float> plane;
    for (uint8_t b : bytes) plane.push_back(b / 255.0f);
    folder_.write("checker.png", testing::png(3, 3, 1, bytes));
    folder_.write("checker.exr", testing::exr(3, 3, {"Y"}, {plane}));
    const auto image_of = [&](const std::string& file) {
        LoadedScene s = load(R"({"camera": {"position": [0, 0, 3], "look_at": [0, 0, 0], "fov": 50},
            "film": {"width": 24, "height": 24, "spp": 4, "background": 1},)" +
                             quad_scene(R"({"albedo": {"texture": ")" + file + R"("}})").substr(1));
        return testing::render(s)->film().mean();
    };
    const Image png_image = image_of("checker.png"), exr_image = image_of("checker.exr");
    EXPECT_EQ(png_image.rgb, exr_image.rgb);
}

// Under a uniform white sky and nothing else, a diffuse quad's radiance is its albedo: the
// image shows the texture's decoded values.
TEST_F(SceneTextures, ATexturedQuadUnderAUniformSkyShowsTheDecodedTexture) {
    // The quadrants at twice the size: within a texel of each quadrant's centre, the bilinear
    // lookup mixes only texels of its colour.
    std::vector<uint8_t> doubled;
    for (int y = 0; y < 4; ++y)
        for (int x = 0; x < 4; ++x)
            for (int c = 0; c < 3; ++c) doubled.push_back(kQuadrants[size_t(3 * (2 * (y / 2) + x / 2) + c)]);
    folder_.write("quadrants4.png", testing::png(4, 4, 3, doubled));
    LoadedScene s = load(R"({"camera": {"position": [0, 0, 2], "look_at": [0, 0, 0], "fov": 53.13},
        "film": {"width": 20, "height": 20, "spp": 64, "background": 1, "filter": "box"},)" +
                         quad_scene(R"({"albedo": {"texture": "quadrants4.png"}})").substr(1));
    const auto job = testing::render(s);
    // The 2×2 pixels around each quadrant's centre (5 pixels of 20 from the edges).
    const Image image = job->film().mean();
    const auto pixel = [&](int x, int y) { return image.at(x, y); };
    const Rgb expected[2][2] = {{{1, 0, 0}, {0, 1, 0}}, {{0, 0, 1}, {1, 1, 1}}};  // [row from top][column]
    for (int row = 0; row < 2; ++row)
        for (int column = 0; column < 2; ++column) {
            const int x = 4 + 10 * column, y = 4 + 10 * row;
            const Rgb p = (pixel(x, y) + pixel(x + 1, y) + pixel(x, y + 1) + pixel(x + 1, y + 1)) * 0.25;
            for (int c = 0; c < 3; ++c) EXPECT_NEAR(p[c], expected[row][column][c], 0.02) << row << column << c;
        }
}

}  // namespace
}  // namespace glint

namespace glint {
namespace {

// The quad's left half opaque, its right half a hole: a grey-and-alpha texture of two texels.
class CutOuts : public SceneTextures {
protected:
    CutOuts() { folder_.write("half.png", testing::png(2, 1, 2, {200, 255, 200, 0})); }
};

TEST_F(CutOuts, RaysPassThroughTheHolesOnly) {
    const LoadedScene s = load(quad_scene(R"({"alpha": {"texture": "half.png"}})"));
    const Geometry& g = s.scene->geometry();
    for (double y : {-0.9, -0.3, 0.4, 0.8}) {
        Hit hit;
        const Ray opaque{{-0.5, y, 3}, {0, 0, -1}}, hole{{0.5, y, 3}, {0, 0, -1}};
        EXPECT_TRUE(g.intersect(opaque, kNoPrimitive, hit));
        EXPECT_FALSE(g.intersect(hole, kNoPrimitive, hit));
        EXPECT_TRUE(g.occluded(opaque, kNoPrimitive));
        EXPECT_FALSE(g.occluded(hole, kNoPrimitive));
        // The cut-off: alpha runs from 1 to 0 between the texel centres, 0.5 at u = 0.5 (x = 0).
        EXPECT_TRUE(g.occluded(Ray{{-0.01, y, 3}, {0, 0, -1}}, kNoPrimitive));
        EXPECT_FALSE(g.occluded(Ray{{0.01, y, 3}, {0, 0, -1}}, kNoPrimitive));
    }
    const LoadedScene stricter = load(quad_scene(R"({"alpha": {"texture": "half.png"}, "alpha_cutoff": 0.9})"));
    EXPECT_FALSE(stricter.scene->geometry().occluded(Ray{{-0.1, 0, 3}, {0, 0, -1}}, kNoPrimitive));
}

// A light above, the cut-out quad below it and a floor below that, seen from between the quad
// and the floor: the floor is in shadow under the opaque half only (black, so that it sends none
// of the floor's light back down).
TEST_F(CutOuts, ShadowsHaveTheirShape) {
    LoadedScene s = load(R"({"camera": {"position": [0, 0, -0.2], "direction": [0, 0, -1], "up": [0, 1, 0], "fov": 90},
        "film": {"width": 16, "height": 8, "spp": 64},)" +
                         quad_scene(R"({"albedo": 0, "alpha": {"texture": "half.png"}})", R"(,
        {"type": "mesh", "vertices": [[-9, -9, -1], [9, -9, -1], [9, 9, -1], [-9, 9, -1]], "indices": [[0, 1, 2], [0, 2, 3]]},
        {"type": "mesh", "emission": 50, "vertices": [[-0.2, -0.2, 3], [0.2, -0.2, 3], [0.2, 0.2, 3], [-0.2, 0.2, 3]], "indices": [[0, 2, 1], [0, 3, 2]]})")
                             .substr(1));
    const Image image = testing::render(s)->film().mean();
    double left = 0, right = 0;
    for (int y = 2; y < 6; ++y)
        for (int x = 0; x < 4; ++x) {
            // The floor from x = -1.2 to -0.4 and from 0.4 to 1.2 (the view is 3.2 wide).
            left += luminance(image.at(2 + x, y));
            right += luminance(image.at(10 + x, y));
        }
    EXPECT_GT(right, 0.5);
    EXPECT_LT(left, 0.1 * right) << left << " " << right;
}

}  // namespace
}  // namespace glint

namespace glint {
namespace {

// A normal map of one texel leaning 45° toward the tangent (+u), on quads whose u runs along +x
// and, mirrored, along -x: the shading normal leans toward +x and -x.
TEST_F(SceneTextures, ANormalMapLeansTheShadingNormalAlongTheTangentFrame) {
    folder_.write("lean.png", testing::png(1, 1, 3, {218, 128, 218}));
    folder_.write("flat.png", testing::png(1, 1, 3, {128, 128, 255}));
    const auto shading_normal = [&](const std::string& uvs, const std::string& map) {
        const LoadedScene s = load(R"({"objects": [{"type": "mesh", "vertices": [[-1, -1, 0], [1, -1, 0], [1, 1, 0], [-1, 1, 0]],
            "uvs": )" + uvs + R"(, "indices": [[0, 1, 2], [0, 2, 3]], "material": {"normal_map": {"texture": ")" + map + R"("}}}]})");
        const Ray ray{{0.3, 0.2, 3}, {0, 0, -1}};
        Hit hit;
        EXPECT_TRUE(s.scene->geometry().intersect(ray, kNoPrimitive, hit));
        EXPECT_FALSE(s.scene->flags(hit.prim).is_diffuse());  // a normal-mapped Lambertian is glossy
        return s.scene->interaction(ray, hit).shading_normal();
    };
    const std::string forward = "[[0, 0], [1, 0], [1, 1], [0, 1]]", mirrored = "[[1, 0], [0, 0], [0, 1], [1, 1]]";
    const double c = (2 * 218 / 255.0 - 1) / std::hypot(2 * 218 / 255.0 - 1, 2 * 218 / 255.0 - 1);
    const Vec3 lean = shading_normal(forward, "lean.png"), back = shading_normal(mirrored, "lean.png");
    EXPECT_NEAR(lean.x, c, 0.01);
    EXPECT_NEAR(lean.z, c, 0.01);
    EXPECT_NEAR(back.x, -c, 0.01);
    EXPECT_NEAR(back.z, c, 0.01);
    EXPECT_NEAR(shading_normal(forward, "flat.png").z, 1, 1e-4);
}

}  // namespace
}  // namespace glint
