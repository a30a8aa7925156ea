// AOVs (render/aov.h): the first diffuse vertex's albedo and normal and the first hit's depth,
// seen directly, through a mirror and through glass; averaged over the image's samples,
// bit-identical whatever the thread count or resume, and free of any effect on the image.
#include <gtest/gtest.h>

#include "io/image_io.h"
#include "support/test_support.h"

namespace glint {
namespace {

using testing::render;
using testing::scene_from;

// A diffuse square at z = 0 facing +z (or at z = 6 facing -z, behind the camera, with `ball` at
// the origin), seen from (0, 0, 4) with a field narrow enough that every pixel sees the ball or
// the square.
LoadedScene plane_scene(const std::string& ball) {
    const std::string z = ball.empty() ? "0" : "6";
    std::string text = R"({"camera": {"position": [0, 0, 4], "look_at": [0, 0, 0], "fov": 10},
        "film": {"width": 8, "height": 8, "spp": 8, "background": 0.5, "aovs": true},
        "objects": [{"type": "mesh", "vertices": [[-40, -40, Z], [40, -40, Z], [40, 40, Z], [-40, 40, Z]],
                     "indices": [[0, 1, 2], [0, 2, 3]], "material": {"albedo": [0.25, 0.5, 0.75]}})";
    for (size_t at; (at = text.find("Z")) != std::string::npos;) text.replace(at, 1, z);
    if (!ball.empty())
        text += R"(, {"type": "sphere", "center": [0, 0, 0], "radius": 1, "material": )" + ball + "}";
    return scene_from(text + "]}");
}

void expect_plane_features(const Film& film, const Vec3& normal) {
    const Image albedo = film.albedo(), normals = film.normal();
    for (int y = 0; y < film.height(); ++y)
        for (int x = 0; x < film.width(); ++x) {
            EXPECT_EQ(albedo.at(x, y), (Rgb{0.25, 0.5, 0.75})) << x << ", " << y;
            EXPECT_EQ(normals.at(x, y), normal) << x << ", " << y;
        }
}

TEST(Aovs, ADiffusePlaneSeenDirectlyGivesItsAlbedoNormalAndDistance) {
    const auto job = render(plane_scene(""));
    expect_plane_features(job->film(), Vec3{0, 0, 1});
    // The rays leave at most 5°·√2 off the axis (the corners of a 10° square view): they meet
    // the plane 4 to 4/cos 7.1° = 4.031 from the eye.
    for (float d : job->film().depth().rgb) {
        EXPECT_GE(d, 4.0f);
        EXPECT_LE(d, 4.031f);
    }
}

// Through specular vertices the AOVs are the plane's, facing the reflected or refracted ray,
// and the depth the ball's own.
TEST(Aovs, AMirrorOrGlassBallShowsThePlaneItReflectsOrRefracts) {
    const auto mirror = render(plane_scene(R"({"type": "mirror", "albedo": 0.9})"));
    expect_plane_features(mirror->film(), Vec3{0, 0, -1});
    const Image depth = mirror->film().depth();
    for (float d : depth.rgb) {
        EXPECT_GE(d, 3.0f);
        EXPECT_LE(d, 3.1f);
    }
}

// Through a glass ball in front of the plane the refracted branch meets the plane; the reflected
// one would leave towards the background.
TEST(Aovs, TheRefractedBranchOfGlassGivesThem) {
    LoadedScene s = scene_from(R"({"camera": {"position": [0, 0, 4], "look_at": [0, 0, 0], "fov": 4},
        "film": {"width": 4, "height": 4, "spp": 8, "background": 0.5, "aovs": true},
        "objects": [{"type": "mesh", "vertices": [[-40, -40, -3], [40, -40, -3], [40, 40, -3], [-40, 40, -3]],
                     "indices": [[0, 1, 2], [0, 2, 3]], "material": {"albedo": [0.25, 0.5, 0.75]}},
                    {"type": "sphere", "center": [0, 0, 0], "radius": 1, "material": {"type": "glass", "albedo": 1}}]})");
    const auto job = render(s);
    expect_plane_features(job->film(), Vec3{0, 0, 1});
}

TEST(Aovs, AMissGivesZeroes) {
    const auto job = render(scene_from(R"({"camera": {"position": [0, 0, 4], "look_at": [0, 0, 0], "fov": 10},
        "film": {"width": 4, "height": 4, "spp": 4, "background": 0.5, "aovs": true},
        "objects": [{"type": "sphere", "center": [0, 0, 9], "radius": 1}]})"));
    for (const Image& image : {job->film().albedo(), job->film().normal(), job->film().depth()})
        for (float v : image.rgb) EXPECT_EQ(v, 0.0f);
}

// Bytes of every AOV image, whole and per half.
std::vector<uint8_t> aov_bytes(const Film& film) {
    std::vector<uint8_t> bytes;
    for (AovLayer layer : {AovLayer::albedo, AovLayer::normal, AovLayer::depth})
        for (AovHalf half : {AovHalf::all, AovHalf::first, AovHalf::second}) {
            const std::vector<uint8_t> pfm = encode_pfm(film.aov(layer, half));
            bytes.insert(bytes.end(), pfm.begin(), pfm.end());
        }
    return bytes;
}

LoadedScene cornell_with_aovs(uint32_t spp) {
    LoadedScene s = testing::small_cornell(spp);
    s.settings.aovs = true;
    return s;
}

TEST(Aovs, AreBitIdenticalWithOneOrTwoThreadsAndLeaveTheImageAsItIs) {
    const LoadedScene s = cornell_with_aovs(8);
    const auto one = render(s, 1), two = render(s, 2);
    EXPECT_EQ(aov_bytes(one->film()), aov_bytes(two->film()));
    EXPECT_TRUE(one->film().has_aovs());
    LoadedScene without = s;
    without.settings.aovs = false;
    const auto plain = render(without);
    EXPECT_FALSE(plain->film().has_aovs());
    EXPECT_TRUE(plain->film().aovs().empty());
    EXPECT_EQ(plain->film().albedo().width, 0);
    EXPECT_EQ(encode_pfm(plain->film().mean()), encode_pfm(one->film().mean()));
}

TEST(Aovs, AResumedJobKeepsThemBitIdentical) {
    const LoadedScene s = cornell_with_aovs(16);
    ThreadPool pool(2);
    RenderJob whole(s.scene, s.settings), first(s.scene, s.settings), rest(s.scene, s.settings);
    whole.run(pool);
    first.render_pass(pool, 0, 8);
    rest.resume(first.film(), 8);
    rest.run(pool);
    EXPECT_EQ(aov_bytes(whole.film()), aov_bytes(rest.film()));
    RenderJob plain(s.scene, [&] {
        RenderSettings settings = s.settings;
        settings.aovs = false;
        return settings;
    }());
    EXPECT_THROW(plain.resume(first.film(), 8), std::invalid_argument);
}

}  // namespace
}  // namespace glint
