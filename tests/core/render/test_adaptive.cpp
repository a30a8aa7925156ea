// Adaptive sampling: the mask's rule (threshold, minimum, 3×3 dilation), determinism (threads,
// resume, split and merge), light tracing's normalisation, and that the image converges to the
// non-adaptive one.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "assembly/partial_file.h"
#include "support/test_support.h"

namespace glint {
namespace {

// The Cornell box at 40×30 with adaptive sampling.
LoadedScene adaptive_cornell(uint32_t spp, double threshold, uint32_t min_spp = 0) {
    LoadedScene s = testing::small_cornell(spp);
    s.settings.adaptive.threshold = threshold;
    s.settings.adaptive.min_spp = min_spp;
    return s;
}

void expect_same_film(const Film& a, const Film& b) {
    ASSERT_EQ(a.pixels().size(), b.pixels().size());
    EXPECT_EQ(a.light_paths(), b.light_paths());
    for (size_t i = 0; i < a.pixels().size(); ++i) {
        const PixelSums &p = a.pixels()[i], &q = b.pixels()[i];
        ASSERT_EQ(p.count, q.count) << "pixel " << i;
        ASSERT_EQ(p.half_count, q.half_count) << "pixel " << i;
        for (int c = 0; c < 3; ++c) {
            ASSERT_EQ(p.sum[c], q.sum[c]) << "pixel " << i;
            ASSERT_EQ(p.half_sum[c], q.half_sum[c]) << "pixel " << i;
            ASSERT_EQ(p.splat[size_t(c)], q.splat[size_t(c)]) << "pixel " << i;
        }
    }
}

// The mean of the pixel means of a block (channel c), with its standard error. Unlike
// testing::pooled, which weighs pixels by their sample counts (all equal without adaptive
// sampling), each pixel counts once, as in the image.
testing::Estimate block_mean(const Film& film, int c, int x0, int y0, int x1, int y1) {
    const double spp = film.samples_per_pixel();
    double sum = 0, var = 0;
    for (int y = y0; y < y1; ++y)
        for (int x = x0; x < x1; ++x) {
            const PixelSums& px = film.pixel(x, y);
            sum += px.sum[c] / double(px.count) + film.splat_mean(px, spp)[c];
            var += Film::camera_variance(px, c) + film.splat_variance(px, c, spp);
        }
    const double pixels = double(x1 - x0) * (y1 - y0);
    return {sum / pixels, std::sqrt(var) / pixels};
}
testing::Estimate image_mean(const Film& film, int c) { return block_mean(film, c, 0, 0, film.width(), film.height()); }

uint64_t fewest(const Film& film) {
    uint64_t n = UINT64_MAX;
    for (const PixelSums& px : film.pixels()) n = std::min(n, px.count);
    return n;
}
uint64_t most(const Film& film) {
    uint64_t n = 0;
    for (const PixelSums& px : film.pixels()) n = std::max(n, px.count);
    return n;
}

// A film whose pixels all have `spp` samples of the value 0.5 in both halves (no error), but for
// one pixel whose halves disagree.
Film flat_film_with_noisy_pixel(int w, int h, uint32_t spp, int nx, int ny) {
    Film film(w, h);
    std::vector<Rgb> round(4, Rgb{0.5});
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x)
            for (uint32_t s = 0; s < spp; s += 4) {
                const bool first = s / 4 % 2 == 0;
                if (x == nx && y == ny) std::fill(round.begin(), round.end(), Rgb{first ? 0.1 : 0.9});
                film.add_round(x, y, round, first);
                std::fill(round.begin(), round.end(), Rgb{0.5});
            }
    return film;
}

TEST(AdaptiveMask, ConvergedPixelsStopUnlessANeighbourIsNoisy) {
    AdaptiveSettings settings{0.01, 16, 0};
    AdaptiveMask mask(settings, 64, 8, 6);
    EXPECT_EQ(mask.active_pixels(), 48u);  // before any decision, every pixel samples
    mask.update(flat_film_with_noisy_pixel(8, 6, 16, 3, 2));
    for (int y = 0; y < 6; ++y)
        for (int x = 0; x < 8; ++x)
            EXPECT_EQ(mask.active(x, y), std::abs(x - 3) <= 1 && std::abs(y - 2) <= 1) << x << ", " << y;
    EXPECT_EQ(mask.active_pixels(), 9u);
}

TEST(AdaptiveMask, NoPixelStopsBeforeTheMinimum) {
    AdaptiveMask mask(AdaptiveSettings{0.01, 32, 0}, 64, 8, 6);
    mask.update(flat_film_with_noisy_pixel(8, 6, 16, 3, 2));
    EXPECT_EQ(mask.active_pixels(), 48u);
    mask.update(flat_film_with_noisy_pixel(8, 6, 32, 3, 2));
    EXPECT_EQ(mask.active_pixels(), 9u);
}

TEST(AdaptiveMask, APartScalesTheThresholdAndTheAutomaticMinimumFollowsIt) {
    const AdaptiveMask whole(AdaptiveSettings{0.01, 0, 0}, 256, 1, 1);
    const AdaptiveMask quarter(AdaptiveSettings{0.01, 0, 256}, 64, 1, 1);
    EXPECT_DOUBLE_EQ(whole.threshold(), 0.01);
    EXPECT_DOUBLE_EQ(quarter.threshold(), 0.02);  // sqrt(256 / 64) × 0.01
    EXPECT_EQ(whole.min_spp(), 48u);              // 4 / sqrt(0.01) = 40, to a check: 48
    EXPECT_EQ(quarter.min_spp(), 32u);            // 4 / sqrt(0.02) = 28.3 -> 32
    EXPECT_EQ(AdaptiveMask(AdaptiveSettings{0.01, 20, 0}, 256, 1, 1).min_spp(), 20u);
}

TEST(Adaptive, PixelsStopAtChecksAndTheMinimumIsHonoured) {
    const auto job = testing::render(adaptive_cornell(128, 0.05, 32));
    EXPECT_EQ(fewest(job->film()), 32u);  // some pixels stop at the minimum, none before
    EXPECT_EQ(most(job->film()), 128u);   // and some sample to the end
    for (const PixelSums& px : job->film().pixels()) EXPECT_EQ(px.count % AdaptiveMask::kCheckInterval, 0u);
    const Progress p = job->progress();
    EXPECT_EQ(p.spp_done, 128u);
    EXPECT_LT(p.mean_spp, 128);
    EXPECT_LT(p.active_pixels, p.pixels);
}

TEST(Adaptive, TheImageDoesNotDependOnTheThreadCount) {
    const LoadedScene s = adaptive_cornell(96, 0.05, 16);
    const auto one = testing::render(s, 1), two = testing::render(s, 2);
    EXPECT_LT(fewest(one->film()), 96u);  // the mask did stop pixels
    expect_same_film(one->film(), two->film());
}

// A checkpoint taken between passes (at 48 samples), resumed by a new job, ends with the film of
// an uninterrupted run: the mask is recomputed from the film alone.
TEST(Adaptive, AResumedRenderEqualsAnUninterruptedOne) {
    const LoadedScene s = adaptive_cornell(96, 0.05, 16);
    const auto whole = testing::render(s);
    ThreadPool pool(2);
    RenderJob first(s.scene, s.settings);
    std::optional<Film> checkpoint;
    first.run(pool, [&](const Progress& p) {
        if (p.spp_done == 48) {
            checkpoint = first.film();
            first.cancel();
        }
    });
    ASSERT_TRUE(checkpoint);
    RenderJob resumed(s.scene, s.settings);
    resumed.resume(*checkpoint, 48);
    resumed.run(pool);
    expect_same_film(resumed.film(), whole->film());
}

LoadedScene small_caustic() {
    return testing::small_scene("caustic.json", 32, 24, 64);
}

// Light tracing, whole image: a stopped pixel traces no light paths, and the splats are divided
// by the light paths traced, one per camera sample taken: the image still agrees with a plain one.
TEST(Adaptive, StoppedPixelsTraceNoLightPathsAndSplatsStayNormalised) {
    LoadedScene s = small_caustic();
    s.settings.spp = 128;
    const auto plain = testing::render(s);
    s.settings.seed = 5;
    s.settings.adaptive = AdaptiveSettings{0.1, 16, 0};
    const auto adaptive = testing::render(s);
    const Film& a = adaptive->film();
    ASSERT_LT(fewest(a), 128u);
    EXPECT_EQ(a.light_paths(), 0u);
    EXPECT_LT(a.samples_per_pixel(), 100);
    EXPECT_EQ(a.samples_per_pixel(), a.camera_samples_per_pixel());
    for (int c = 0; c < 3; ++c) {
        const testing::Estimate x = image_mean(a, c), y = image_mean(plain->film(), c);
        EXPECT_LT(std::abs(x.mean - y.mean), 4 * std::hypot(x.sigma, y.sigma)) << "channel " << c;
    }
}

// Light tracing, region job: pixels outside the window trace every sample's light paths, so the
// window's stopped pixels trace theirs too; the film counts them, and the splats are a plain
// region render's, bit for bit.
TEST(Adaptive, ARegionJobTracesTheLightPathsOfItsStoppedPixels) {
    LoadedScene s = small_caustic();
    s.settings.region = {8, 6, 24, 18};
    const auto plain = testing::render(s);
    s.settings.adaptive = AdaptiveSettings{0.1, 16, 0};
    const auto adaptive = testing::render(s);
    const Film &a = adaptive->film(), &b = plain->film();
    ASSERT_LT(fewest(a), 64u);
    EXPECT_EQ(a.light_paths(), 64u);
    EXPECT_EQ(a.samples_per_pixel(), b.samples_per_pixel());
    for (size_t i = 0; i < a.pixels().size(); ++i)
        for (size_t c = 0; c < 3; ++c) ASSERT_EQ(a.pixels()[i].splat[c], b.pixels()[i].splat[c]) << "pixel " << i;
    // The count goes through a partial file.
    const Partial p = decode_partial(encode_partial(partial_of(*adaptive, 0, 64)));
    EXPECT_EQ(p.film.light_paths(), 64u);
}

// Each part adapts on its own samples against the scaled threshold; the merge adds sums.
Film merged_parts(LoadedScene s, unsigned threads) {
    s.settings.adaptive.job_spp = s.settings.spp;
    s.settings.spp /= 2;
    Film merged = testing::render(s, threads)->film();
    s.settings.first_sample = s.settings.spp;
    merged.merge(testing::render(s, threads)->film());
    return merged;
}

TEST(Adaptive, ASplitJobMergesDeterministicallyAndAgreesWithTheWhole) {
    const LoadedScene s = adaptive_cornell(128, 0.05, 16);
    const Film once = merged_parts(s, 1), twice = merged_parts(s, 2);
    expect_same_film(once, twice);
    EXPECT_LT(fewest(once), 128u);
    const auto whole = testing::render(s);
    for (int c = 0; c < 3; ++c) {
        const testing::Estimate a = image_mean(once, c), b = image_mean(whole->film(), c);
        EXPECT_LT(std::abs(a.mean - b.mean), 4 * std::hypot(a.sigma, b.sigma)) << "channel " << c;
    }
}

// At many samples an adaptive render agrees with a plain one of another seed, block by block
// (8×6 blocks, each pooled with its standard error).
void expect_agrees_with_plain_render(LoadedScene s, double threshold) {
    const auto plain = testing::render(s);
    s.settings.seed = 7;
    s.settings.adaptive.threshold = threshold;
    const auto adaptive = testing::render(s);
    EXPECT_LT(fewest(adaptive->film()), s.settings.spp);
    double chi2 = 0;
    int blocks = 0;
    for (int y = 0; y < s.settings.height; y += 6)
        for (int x = 0; x < s.settings.width; x += 8)
            for (int c = 0; c < 3; ++c) {
                const testing::Estimate a = block_mean(adaptive->film(), c, x, y, x + 8, y + 6),
                                        b = block_mean(plain->film(), c, x, y, x + 8, y + 6);
                const double z = (a.mean - b.mean) / std::max(1e-12, std::hypot(a.sigma, b.sigma));
                EXPECT_LT(std::abs(z), 5) << "block " << x << ", " << y << " channel " << c;
                chi2 += z * z;
                ++blocks;
            }
    EXPECT_LT(chi2 / blocks, 2.0);  // about 1 if the two agree within their noise
}

TEST(Adaptive, ConvergesToThePlainImageOnTheCornellBox) {
    expect_agrees_with_plain_render(testing::small_cornell(256), 0.02);
}

TEST(Adaptive, ConvergesToThePlainImageOnTheMeshScene) {
    LoadedScene s = testing::small_scene("mesh.json", 40, 30, 256);
    expect_agrees_with_plain_render(s, 0.02);
}

}  // namespace
}  // namespace glint
