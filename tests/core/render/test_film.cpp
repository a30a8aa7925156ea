// The film: sums, the error estimate's formula from the two halves of the rounds, and samples
// that are NaN or infinite.
#include <gtest/gtest.h>

#include "render/film.h"
#include "io/image_io.h"

namespace glint {
namespace {

void add_round(Film& film, int x, int y, const std::vector<Rgb>& samples, bool first_half = true) {
    film.add_round(x, y, samples, first_half);
}

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN(), kInf = std::numeric_limits<double>::infinity();

TEST(Film, DropsAndCountsWholeRoundsWithANonFiniteSample) {
    Film film(2, 1);
    add_round(film, 0, 0, {Rgb{1}, Rgb{3}});
    add_round(film, 0, 0, {Rgb{5}, Rgb{kNaN, 0, 0}}, false);  // the 5 goes too: its round is incomplete
    add_round(film, 0, 0, {Rgb{0, kInf, 0}, Rgb{7}});
    add_round(film, 1, 0, {Rgb{0, 0, -kInf}, Rgb{1}});
    EXPECT_EQ(film.dropped(), 6u);
    EXPECT_EQ(film.pixel(0, 0).count, 2u);
    EXPECT_EQ(film.pixel(0, 0).half_count, 2u);
    EXPECT_EQ(film.pixel(0, 0).half_sum, Rgb{4});
    EXPECT_EQ(film.samples_per_pixel(), 4.0);  // dropped samples were taken: light paths were traced
    const Image image = film.mean();
    EXPECT_EQ(image.at(0, 0), Rgb{2});
    EXPECT_EQ(image.at(1, 0), Rgb{0});  // no samples yet: black, not NaN
    for (float v : image.rgb) EXPECT_TRUE(std::isfinite(v));
}

TEST(Film, ErrorEstimateIsTheStandardErrorOfThePixelMeanFromItsHalves) {
    Film film(2, 1);
    // Pixel 0: halves {0, 4} and {0, 4}: their means agree (2 and 2), so the mean has no error,
    // although the samples spread (the spread of stratified samples within a round). Pixel 1:
    // halves {0, 2} and {2, 4}: means 1 and 3, the pixel's mean (1 + 3)/2 has variance
    // (3 - 1)²/4 = 1. Average over 6 channel values of 0,0,0,1,1,1 = 0.5.
    add_round(film, 0, 0, {Rgb{0}, Rgb{4}}, true);
    add_round(film, 0, 0, {Rgb{0}, Rgb{4}}, false);
    add_round(film, 1, 0, {Rgb{0}, Rgb{2}}, true);
    add_round(film, 1, 0, {Rgb{2}, Rgb{4}}, false);
    EXPECT_DOUBLE_EQ(film.error_estimate(), std::sqrt(0.5));
    // Merged from films of one round each, the film is the same.
    Film first(2, 1), second(2, 1);
    add_round(first, 0, 0, {Rgb{0}, Rgb{4}}, true);
    add_round(second, 0, 0, {Rgb{0}, Rgb{4}}, false);
    add_round(first, 1, 0, {Rgb{0}, Rgb{2}}, true);
    add_round(second, 1, 0, {Rgb{2}, Rgb{4}}, false);
    first.merge(second);
    EXPECT_DOUBLE_EQ(first.error_estimate(), std::sqrt(0.5));
}

// A dropped round leaves the halves unequal: n0 = 2 samples of mean 1 and n1 = 4 of mean 3. The
// mean's variance is V/6 where the halves' are V/2 and V/4, so E[(m0 - m1)²] = 3V/4 and the
// estimate is (m0 - m1)²·(2/9) = 8/9.
TEST(Film, ErrorEstimateWeighsUnequalHalves) {
    Film film(1, 1);
    add_round(film, 0, 0, {Rgb{1}, Rgb{1}}, true);
    add_round(film, 0, 0, {Rgb{3}, Rgb{3}}, false);
    add_round(film, 0, 0, {Rgb{3}, Rgb{3}}, false);
    EXPECT_DOUBLE_EQ(film.error_estimate(), std::sqrt(8.0 / 9));
}

TEST(Film, ErrorEstimateIsInfiniteUntilEveryPixelHasBothHalves) {
    Film film(2, 1);
    add_round(film, 0, 0, {Rgb{1}, Rgb{2}, Rgb{3}, Rgb{4}}, true);
    add_round(film, 1, 0, {Rgb{1}, Rgb{2}, Rgb{3}, Rgb{4}}, true);
    add_round(film, 1, 0, {Rgb{1}, Rgb{2}, Rgb{3}, Rgb{4}}, true);
    EXPECT_TRUE(std::isinf(film.error_estimate()));  // two rounds, but of one half
    add_round(film, 0, 0, {Rgb{1}, Rgb{2}, Rgb{3}, Rgb{4}}, false);
    EXPECT_TRUE(std::isinf(film.error_estimate()));
    add_round(film, 1, 0, {Rgb{2.5}, Rgb{2.5}, Rgb{2.5}, Rgb{2.5}}, false);
    EXPECT_EQ(film.error_estimate(), 0);
}

TEST(Film, SplatsAddExactlyInAnyOrderAndDivideByTheSamplesPerPixel) {
    // Values that double addition would round differently in different orders.
    const double values[] = {1e-3, 0.1, 0.7, 3e-5, 0.25};
    Film forward(2, 1), backward(2, 1);
    for (double v : values) forward.splat(1, 0, Rgb{v});
    for (int i = 4; i >= 0; --i) backward.splat(1, 0, Rgb{values[i]});
    EXPECT_EQ(forward.pixel(1, 0).splat, backward.pixel(1, 0).splat);
    // Two camera samples per pixel: the splats are an estimate over 2 light paths per pixel.
    for (Film* f : {&forward, &backward})
        for (int x = 0; x < 2; ++x) add_round(*f, x, 0, {Rgb{1}, Rgb{1}});
    const Image image = forward.mean();
    EXPECT_NEAR(image.at(1, 0).x, 1 + (1e-3 + 0.1 + 0.7 + 3e-5 + 0.25) / 2, 1e-6);
    EXPECT_EQ(image.at(0, 0), Rgb{1});
    EXPECT_EQ(encode_pfm(image), encode_pfm(backward.mean()));
}

// AOVs are averaged over the samples the image keeps: a round dropped for a NaN takes its AOVs
// along, and the halves' means come from the rounds of each half.
TEST(Film, ADroppedRoundDropsItsAovs) {
    Film film(1, 1, true);
    const Aov a{Rgb{0.5}, Vec3{0, 0, 1}, 2}, b{Rgb{0.25}, Vec3{0, 1, 0}, 4}, odd{Rgb{1}, Vec3{1, 0, 0}, 100};
    const std::vector<Aov> first{a, a}, second{b, b}, dropped{odd, odd};
    film.add_round(0, 0, std::vector<Rgb>{Rgb{1}, Rgb{1}}, true, first);
    film.add_round(0, 0, std::vector<Rgb>{Rgb{1}, Rgb{kNaN}}, false, dropped);
    film.add_round(0, 0, std::vector<Rgb>{Rgb{1}, Rgb{1}}, false, second);
    EXPECT_EQ(film.albedo().at(0, 0), Rgb{0.375});
    EXPECT_EQ(film.normal().at(0, 0), (Vec3{0, 0.5, 0.5}));
    EXPECT_EQ(film.depth().at(0, 0), Rgb{3});
    EXPECT_EQ(film.aov(AovLayer::depth, AovHalf::first).at(0, 0), Rgb{2});
    EXPECT_EQ(film.aov(AovLayer::albedo, AovHalf::second).at(0, 0), Rgb{0.25});
    // Merged from two films of one round each, the same.
    Film one(1, 1, true), other(1, 1, true);
    one.add_round(0, 0, std::vector<Rgb>{Rgb{1}, Rgb{1}}, true, first);
    other.add_round(0, 0, std::vector<Rgb>{Rgb{1}, Rgb{1}}, false, second);
    one.merge(other);
    EXPECT_EQ(encode_pfm(one.normal()), encode_pfm(film.normal()));
    // A film without AOVs keeps none, whatever it is given.
    Film plain(1, 1);
    plain.add_round(0, 0, std::vector<Rgb>{Rgb{1}, Rgb{1}}, true, first);
    EXPECT_TRUE(plain.aovs().empty());
}

TEST(Film, NonFiniteSplatsAreDroppedAndCounted) {
    Film film(1, 1);
    film.splat(0, 0, Rgb{kInf, 0, 0});
    film.splat(0, 0, Rgb{0, kNaN, 0});
    film.splat(0, 0, Rgb{1e300});  // beyond the fixed-point range
    add_round(film, 0, 0, {Rgb{0.5}});
    EXPECT_EQ(film.dropped(), 3u);
    EXPECT_EQ(film.mean().at(0, 0), Rgb{0.5});
}

}  // namespace
}  // namespace glint
