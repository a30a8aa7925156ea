// Region renders: a window's pixels are the whole render's, bit for bit, because every random
// stream is keyed by (seed, pixel, sample) and the light paths of pixels outside the window,
// which splat into it, are traced too.
#include <gtest/gtest.h>

#include <cstring>

#include "assembly/fingerprint.h"
#include "base/files.h"
#include "io/image_io.h"
#include "render/strategies.h"
#include "support/test_support.h"

namespace glint {
namespace {

// The whole render and a render of `region`, pixel sums compared byte for byte.
void expect_window_of_whole(const LoadedScene& whole) {
    LoadedScene part = whole;
    part.settings.region = Region{7, 5, 29, 23};  // crosses tile edges on both axes
    const auto a = testing::render(whole, 2), b = testing::render(part, 1);
    ASSERT_EQ(b->film().width(), 22);
    ASSERT_EQ(b->film().height(), 18);
    const Region r = part.settings.region;
    const Image full = a->film().mean(), window = b->film().mean();
    for (int y = r.y0; y < r.y1; ++y)
        for (int x = r.x0; x < r.x1; ++x) {
            const PixelSums &p = a->film().pixel(x, y), &q = b->film().pixel(x - r.x0, y - r.y0);
            ASSERT_EQ(std::memcmp(&p, &q, sizeof p), 0) << "pixel " << x << ", " << y;
            ASSERT_EQ(full.at(x, y), window.at(x - r.x0, y - r.y0)) << "pixel " << x << ", " << y;
        }
}

TEST(Region, PixelsAreThoseOfTheWholeRender) { expect_window_of_whole(testing::small_cornell(8)); }

TEST(Region, PixelsAreThoseOfTheWholeRenderWithLightTracing) {
    // The caustic scene's light paths splat into the window from pixels outside it.
    const std::vector<uint8_t> text = read_file(GLINT_SCENES_DIR "/caustic.json", 1 << 20);
    LoadedScene s = testing::scene_from(std::string(text.begin(), text.end()));
    ASSERT_TRUE(Strategies(*s.scene).light_tracing());
    s.settings.width = 40;
    s.settings.height = 30;
    s.settings.spp = 8;
    expect_window_of_whole(s);
}

TEST(Region, FingerprintNamesTheWindow) {
    LoadedScene s = testing::small_cornell(8);
    RenderSettings part = s.settings;
    part.region = Region{0, 0, 20, 30};
    EXPECT_NE(fingerprint(*s.scene, s.settings), fingerprint(*s.scene, part));
}

TEST(Preview, IsShownFirstAndLeavesTheImageAsItWas) {
    LoadedScene s = testing::small_cornell(8);
    s.settings.region = Region{3, 4, 30, 20};
    ThreadPool pool(2);
    RenderJob with(s.scene, s.settings), without(s.scene, s.settings);
    int previews = 0, passes_before = -1, passes = 0;
    with.run(pool, [&](const Progress&) { ++passes; }, [&](const Image& preview) {
        ++previews;
        passes_before = passes;
        EXPECT_EQ(preview.width, 27);
        EXPECT_EQ(preview.height, 16);
        double total = 0;
        for (float v : preview.rgb) total += v;
        EXPECT_GT(total, 0);  // lit, and finite
        EXPECT_TRUE(std::isfinite(total));
    });
    without.run(pool);
    EXPECT_EQ(previews, 1);
    EXPECT_EQ(passes_before, 0);
    EXPECT_EQ(encode_pfm(with.film().mean()), encode_pfm(without.film().mean()));
}

}  // namespace
}  // namespace glint
