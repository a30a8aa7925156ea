// The film: sums, the error estimate's formula, and samples that are NaN or infinite.
#include <gtest/gtest.h>

#include "film.h"
#include "image_io.h"

namespace glint {
namespace {

TEST(Film, DropsAndCountsNonFiniteSamples) {
    Film film(2, 1);
    film.add(0, 0, Rgb{1});
    film.add(0, 0, Rgb{std::numeric_limits<double>::quiet_NaN(), 0, 0});
    film.add(0, 0, Rgb{0, std::numeric_limits<double>::infinity(), 0});
    film.add(0, 0, Rgb{3});
    film.add(1, 0, Rgb{0, 0, -std::numeric_limits<double>::infinity()});
    EXPECT_EQ(film.dropped(), 3u);
    EXPECT_EQ(film.pixel(0, 0).count, 2u);
    const Image image = film.mean();
    EXPECT_EQ(image.at(0, 0), Rgb{2});
    EXPECT_EQ(image.at(1, 0), Rgb{0});  // no samples yet: black, not NaN
    for (float v : image.rgb) EXPECT_TRUE(std::isfinite(v));
}

TEST(Film, ErrorEstimateIsTheStandardErrorOfEachPixelMean) {
    Film film(2, 1);
    // Pixel 0 channel values {0, 2}: sample variance 2, variance of the mean 1.
    // Pixel 1: {1, 1}: variance 0. Average over 6 channel values of 1,1,1,0,0,0 = 0.5.
    film.add(0, 0, Rgb{0});
    film.add(0, 0, Rgb{2});
    film.add(1, 0, Rgb{1});
    film.add(1, 0, Rgb{1});
    EXPECT_DOUBLE_EQ(film.error_estimate(), std::sqrt(0.5));
}

TEST(Film, ErrorEstimateIsInfiniteUntilEveryPixelHasTwoSamples) {
    Film film(1, 1);
    film.add(0, 0, Rgb{1});
    EXPECT_TRUE(std::isinf(film.error_estimate()));
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
        for (int x = 0; x < 2; ++x) {
            f->add(x, 0, Rgb{1});
            f->add(x, 0, Rgb{1});
        }
    const Image image = forward.mean();
    EXPECT_NEAR(image.at(1, 0).x, 1 + (1e-3 + 0.1 + 0.7 + 3e-5 + 0.25) / 2, 1e-6);
    EXPECT_EQ(image.at(0, 0), Rgb{1});
    EXPECT_EQ(encode_pfm(image), encode_pfm(backward.mean()));
}

TEST(Film, NonFiniteSplatsAreDroppedAndCounted) {
    Film film(1, 1);
    film.splat(0, 0, Rgb{std::numeric_limits<double>::infinity(), 0, 0});
    film.splat(0, 0, Rgb{0, std::numeric_limits<double>::quiet_NaN(), 0});
    film.splat(0, 0, Rgb{1e300});  // beyond the fixed-point range
    film.add(0, 0, Rgb{0.5});
    EXPECT_EQ(film.dropped(), 3u);
    EXPECT_EQ(film.mean().at(0, 0), Rgb{0.5});
}

}  // namespace
}  // namespace glint
