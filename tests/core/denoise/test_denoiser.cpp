// The denoised preview on synthetic films: a known image plus noise of known variance in both
// halves, so every claim is checked against the truth.
#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <random>

#include "denoise/denoiser.h"
#include "denoise/denoiser_config.h"

namespace glint {
namespace {

using Truth = std::function<Rgb(int x, int y)>;

// A film of `rounds` rounds of 4 samples per pixel, alternating halves: each sample is the
// truth plus Gaussian noise of standard deviation `sigma` (times the truth's brightness when
// `relative`), from a fixed seed.
// With `aovs`, the film keeps AOVs too: the truth as albedo, a fixed normal and depth.
Film noisy_film(int w, int h, const Truth& truth, int rounds, double sigma, uint64_t seed = 7, bool aovs = false) {
    Film film(w, h, aovs);
    std::mt19937_64 rng(seed);
    std::normal_distribution<double> noise(0.0, sigma);
    std::vector<Rgb> samples(4);
    std::vector<Aov> features(4);
    for (int r = 0; r < rounds; ++r)
        for (int y = 0; y < h; ++y)
            for (int x = 0; x < w; ++x) {
                for (Rgb& s : samples) s = truth(x, y) + Rgb{noise(rng), noise(rng), noise(rng)};
                for (Aov& f : features) f = Aov{truth(x, y), Vec3{0, 0, 1}, 2.0};
                film.add_round(x, y, samples, r % 2 == 0, aovs ? std::span<const Aov>(features) : std::span<const Aov>());
            }
    return film;
}

Image truth_image(int w, int h, const Truth& truth) {
    Image image(w, h);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) image.set(x, y, truth(x, y));
    return image;
}

Rgb smooth(int x, int y) { return Rgb{0.5 + 0.3 * std::sin(x * 0.1), 0.4 + 0.2 * std::cos(y * 0.12), 0.6}; }
Rgb edge(int x, int) { return Rgb{x < 24 ? 0.2 : 0.8}; }

Image denoised(const Film& film, unsigned threads = 2) {
    ThreadPool pool(threads);
    return denoise(film, pool);
}

TEST(Denoiser, RemovesMostOfTheNoiseOfASmoothImage) {
    const Film film = noisy_film(48, 40, smooth, 4, 0.2);
    const Image truth = truth_image(48, 40, smooth);
    const double noisy = rmse(film.mean(), truth), filtered = rmse(denoised(film), truth);
    EXPECT_LT(filtered * filtered, noisy * noisy / 8) << noisy << " " << filtered;
}

TEST(Denoiser, LeavesAFilmWithoutNoiseAsItIs) {
    const Truth varied = [](int x, int y) { return Rgb{double((x * 7 + y * 13) % 11) / 10, 0.3, double(x % 3)}; };
    const Film film = noisy_film(40, 32, varied, 4, 0.0);
    EXPECT_EQ(denoised(film).rgb, film.mean().rgb);
}

TEST(Denoiser, KeepsASharpEdgeBetweenFlatRegions) {
    const Film film = noisy_film(48, 40, edge, 4, 0.15);
    const Image image = denoised(film);
    for (int x : {22, 23, 24, 25}) {  // the columns either side of the edge, averaged over rows
        double mean = 0;
        for (int y = 0; y < 40; ++y) mean += image.at(x, y).x / 40;
        EXPECT_NEAR(mean, edge(x, 0).x, 0.03) << "column " << x;
    }
}

// A dark, quiet region beside a bright and very noisy one (a lamp's glow beside a shadow, or a
// caustic beside the dark): the dark pixels by the edge must not take the bright side's light.
// The bright side's noise dwarfs any error in the dark in absolute terms; measured relative to
// each pixel's own level and in units of its own noise, the dark side keeps its value.
TEST(Denoiser, KeepsTheDarkSideOfAnEdgeBesideABrightNoisyRegion) {
    Film film(48, 40);
    std::mt19937_64 rng(11);
    std::exponential_distribution<double> bright(1.0 / 4);  // heavy-tailed, mean 4
    std::normal_distribution<double> quiet(0.02, 0.005);
    std::vector<Rgb> samples(4);
    for (int r = 0; r < 4; ++r)
        for (int y = 0; y < 40; ++y)
            for (int x = 0; x < 48; ++x) {
                for (Rgb& s : samples) s = Rgb{x < 24 ? quiet(rng) : bright(rng)};
                film.add_round(x, y, samples, r % 2 == 0);
            }
    const Image image = denoised(film);
    for (int x = 20; x < 24; ++x)  // the dark columns by the edge, each pixel on its own
        for (int y = 0; y < 40; ++y) EXPECT_LT(image.at(x, y).x, 0.1) << x << "," << y;
}

// Irregular streaks and specks one to three pixels wide (a crowd of small spheres or a room's
// corners at preview size): a 15×15 window finds few neighbours whose 5×5 patches match a pixel
// on one, and many near-matches that blur it; the local filter's 3×3 patches in a 7×7 window
// match the structure's own pixels. (Periodic patterns are the wide window's strength, and are
// left out here: its many matching repeats hide what a scene's one-off structures get.)
TEST(Denoiser, TheLocalFilterKeepsThinIrregularStructuresAndTheirSurroundings) {
    const Truth streaks = [](int x, int y) { return Rgb{(x * x / 7 + y / 9) % 5 == 0 ? 0.8 : 0.15}; };
    const Film film = noisy_film(48, 42, streaks, 4, 0.25, 5);
    DenoiserConfig wide_only;
    wide_only.filters.resize(1);
    ThreadPool pool(2);
    const Image truth = truth_image(48, 42, streaks);
    const double both = rmse(denoise(film, pool), truth);
    const double wide = rmse(denoise_with(half_buffers(film), wide_only, pool), truth);
    EXPECT_LT(both * both, 0.75 * wide * wide) << both << " " << wide;
}

TEST(Denoiser, WithAovsKeepsTheEdgeTheFeaturesShowAndRemovesMoreNoise) {
    const Film plain = noisy_film(48, 40, edge, 4, 0.3), featured = noisy_film(48, 40, edge, 4, 0.3, 7, true);
    const Image truth = truth_image(48, 40, edge), image = denoised(featured);
    EXPECT_LT(rmse(image, truth), rmse(denoised(plain), truth));
    EXPECT_LT(rmse(image, truth), rmse(featured.mean(), truth) / 4);
    for (int y = 0; y < 40; ++y) EXPECT_NEAR(image.at(23, y).x, 0.2, 0.1) << "row " << y;  // beside the edge
    EXPECT_EQ(image.rgb, denoised(featured, 3).rgb);
}

TEST(Denoiser, ConvergesToTheUnbiasedImageAsSamplesGrow) {
    const Film few = noisy_film(40, 32, smooth, 4, 0.2), many = noisy_film(40, 32, smooth, 1024, 0.2);
    const double few_change = rmse(denoised(few), few.mean()), many_change = rmse(denoised(many), many.mean());
    EXPECT_LT(many_change, few_change / 8) << few_change << " " << many_change;
    const Image truth = truth_image(40, 32, smooth);
    EXPECT_LE(rmse(denoised(many), truth), rmse(many.mean(), truth) * 1.05);
}

TEST(Denoiser, SameBytesForAnyThreadCount) {
    const Film film = noisy_film(50, 37, smooth, 4, 0.3);
    const Image one = denoised(film, 1);
    EXPECT_EQ(one.rgb, denoised(film, 2).rgb);
    EXPECT_EQ(one.rgb, denoised(film, 5).rgb);
}

TEST(Denoiser, FiniteOnExtremeAndMissingSamples) {
    Film film = noisy_film(24, 20, smooth, 2, 0.5);
    film.add_round(3, 3, std::vector<Rgb>(4, Rgb{1e30}), true);  // one huge round: one half only
    film.add_round(5, 5, std::vector<Rgb>(4, Rgb{1e-30}), false);
    film.pixels()[size_t(7) * 24 + 7] = PixelSums{};  // a pixel with no samples at all
    film.splat(9, 9, Rgb{1e6});
    for (float v : denoised(film).rgb) ASSERT_TRUE(std::isfinite(v));
    const Film first_round = noisy_film(24, 20, smooth, 1, 0.5);  // no pixel has both halves
    EXPECT_EQ(denoised(first_round).rgb, first_round.mean().rgb);
}

}  // namespace
}  // namespace glint
