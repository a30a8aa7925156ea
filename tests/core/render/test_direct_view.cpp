// Splitting off the direct view where it varies across a pixel (core/render/direct_view.h), on an
// emitter whose edge crosses the image exactly between two columns, where each pixel's value is
// known in closed form.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include "render/direct_view.h"
#include "support/test_support.h"

namespace glint {
namespace {

using testing::pooled;
using testing::render;
using testing::scene_from;

constexpr int kWidth = 16, kHeight = 8, kEdge = 8;  // the emitter covers the columns left of kEdge
constexpr double kEmission = 12;

// An emissive square filling the image left of its centre line, against a black background.
nlohmann::json half_lit(int direct_view_rays) {
    auto scene = nlohmann::json::parse(R"({
        "camera": {"position": [0, 0, 10], "look_at": [0, 0, 0], "fov": 40},
        "film": {"width": 16, "height": 8, "spp": 64, "seed": 3},
        "objects": [{"type": "mesh", "vertices": [[-50, -50, 0], [0, -50, 0], [0, 50, 0], [-50, 50, 0]],
                     "indices": [[0, 1, 2], [0, 2, 3]], "material": {"albedo": 0}, "emission": 12}]})");
    scene["integrator"]["direct_view_rays"] = direct_view_rays;
    return scene;
}

// Which pixels split, as a string per row ('x' splits).
std::vector<std::string> split_map(const nlohmann::json& json) {
    const LoadedScene loaded = scene_from(json.dump());
    const Camera camera(loaded.scene->camera(), kWidth, kHeight);
    const PathTracer tracer(*loaded.scene, camera);
    DirectViewSplit split(*loaded.scene, camera, loaded.settings.filter, kWidth, kHeight, 8);
    split.decide(tracer, camera, 0, 0, kWidth, kHeight);
    std::vector<std::string> rows;
    for (int y = 0; y < kHeight; ++y) {
        rows.emplace_back();
        for (int x = 0; x < kWidth; ++x) rows.back() += split.splits(x, y) ? 'x' : '.';
    }
    return rows;
}

TEST(DirectView, SplitsThePixelsWhoseFootprintTheEdgeCrossesAndNoOthers) {
    // The tent filter's footprint reaches a quarter pixel beyond the pixel on either side, so
    // the edge between columns 7 and 8 lies in both their footprints.
    for (const std::string& row : split_map(half_lit(8))) EXPECT_EQ(row, ".......xx.......");
}

bool active(const nlohmann::json& json, int rays) {
    const LoadedScene loaded = scene_from(json.dump());
    const Camera camera(loaded.scene->camera(), kWidth, kHeight);
    return DirectViewSplit(*loaded.scene, camera, loaded.settings.filter, kWidth, kHeight, rays).active();
}

TEST(DirectView, ProbesOnlyWhereTheCameraCanSeeSomethingToSplit) {
    EXPECT_TRUE(active(half_lit(8), 8));
    EXPECT_FALSE(active(half_lit(8), 0));
    auto scene = half_lit(8);
    scene["objects"][0].erase("emission");  // nothing to see directly
    EXPECT_FALSE(active(scene, 8));
    scene["film"]["background"] = 1;
    EXPECT_TRUE(active(scene, 8));
    scene["film"].erase("background");
    // A mirror ball behind the camera; a glass ball above the view whose bottom reaches into
    // the footprints of the top row (the view spans ±3.64 up and down at the quad's distance,
    // 3.87 with the tent's quarter-pixel margin), then one whose box stays clear of them.
    scene["objects"].push_back({{"type", "sphere"}, {"center", {0, 0, 20}}, {"radius", 1}, {"material", {{"type", "mirror"}}}});
    EXPECT_FALSE(active(scene, 8));
    scene["objects"].push_back({{"type", "sphere"}, {"center", {0, 4.8, 0}}, {"radius", 1}, {"material", {{"type", "glass"}}}});
    EXPECT_TRUE(active(scene, 8));
    scene["objects"].back()["center"] = {0, 5.6, 0};
    EXPECT_FALSE(active(scene, 8));
}

TEST(DirectView, EdgePixelsConvergeToTheFilterWeightedCoverageWithLessVariance) {
    // The tent filter puts 1/16 of a pixel's weight beyond a quarter pixel past its edge (each
    // of the two subpixel tents, of half-width 1/2, puts 1/8 beyond its own half-way point), so
    // the edge column on the lit side has 15/16 of the emission, the other 1/16.
    const auto split = render(scene_from(half_lit(8).dump()));
    const auto whole = render(scene_from(half_lit(0).dump()));
    auto expected = [](int x) { return kEmission * (x < kEdge ? 15.0 / 16 : 1.0 / 16); };
    for (int x : {kEdge - 1, kEdge}) {
        const auto a = pooled(split->film(), 0, x, 0, x + 1, kHeight), b = pooled(whole->film(), 0, x, 0, x + 1, kHeight);
        EXPECT_NEAR(a.mean, expected(x), 4 * a.sigma + 1e-12) << "column " << x;
        EXPECT_NEAR(b.mean, expected(x), 4 * b.sigma + 1e-12) << "column " << x;
    }
    // Eight rays a sample: with independent film positions, eight times less variance, which
    // the squared error against the closed form over 128 edge pixels shows as at least four.
    // (The stratified sampler finds this edge exactly either way: it lies on a dyadic boundary
    // of every subpixel's points.)
    auto independent = [](int rays) {
        LoadedScene s = scene_from(half_lit(rays).dump());
        s.settings.height = 64;
        s.settings.sampler = Sampler::independent;
        return render(s);
    };
    const Image split_image = independent(8)->film().mean(), whole_image = independent(0)->film().mean();
    double split_error = 0, whole_error = 0;
    for (int x : {kEdge - 1, kEdge})
        for (int y = 0; y < 64; ++y) {
            split_error += std::pow(split_image.at(x, y).x - expected(x), 2);
            whole_error += std::pow(whole_image.at(x, y).x - expected(x), 2);
        }
    EXPECT_GT(whole_error, 4 * split_error);
    // Pixels that do not split gather the direct view on the camera path as before.
    for (int x : {0, kEdge - 2, kEdge + 1, kWidth - 1})
        EXPECT_EQ(split->film().mean().at(x, 3), whole->film().mean().at(x, 3)) << "column " << x;
}

}  // namespace
}  // namespace glint
