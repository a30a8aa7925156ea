// The environment's mapping (the README's directions for u and v, the seam, the poles, the
// rotation), its bilinear lookup, and its sampling: the density sample() reports is pdf()'s,
// it integrates to 1, directions fall in each texel's cell as often as the density says, and
// none in the cells below the map's mean (MIS compensation).
#include <gtest/gtest.h>

#include <cmath>

#include "base/rng.h"
#include "scene/environment.h"

namespace glint {
namespace {

// The direction the README gives for image coordinates (u, v) at rotation 0.
Vec3 direction_of(double u, double v) {
    const double phi = 2 * kPi * (u - 0.5), theta = kPi * (0.5 - v);
    return {std::cos(theta) * std::cos(phi), std::sin(theta), std::cos(theta) * std::sin(phi)};
}

// width × height texels, texel (i, j) (j from the top) of value (i, j, 1 + i + width·j).
Environment numbered(int width, int height, EnvironmentSettings settings = {}) {
    std::vector<float> rgb;
    for (int j = 0; j < height; ++j)
        for (int i = 0; i < width; ++i) rgb.insert(rgb.end(), {float(i), float(j), float(1 + i + width * j)});
    return Environment(std::make_shared<const EnvironmentMap>(width, height, std::move(rgb)), settings);
}

void expect_rgb(const Rgb& got, const Rgb& want) {
    EXPECT_NEAR(got.x, want.x, 1e-9);
    EXPECT_NEAR(got.y, want.y, 1e-9);
    EXPECT_NEAR(got.z, want.z, 1e-9);
}

TEST(Environment, TexelCentresAreSeenInTheDocumentedDirections) {
    const Environment env = numbered(8, 4);
    for (int j = 0; j < 4; ++j)
        for (int i = 0; i < 8; ++i)
            expect_rgb(env.radiance(direction_of((i + 0.5) / 8, (j + 0.5) / 4)), {double(i), double(j), 1.0 + i + 8 * j});
    // The image's centre along +x, its three-quarter column along +z, its top row up.
    expect_rgb(env.radiance({1, 0, 0}), env.radiance(direction_of(0.5, 0.5)));
    expect_rgb(env.radiance({0, 0, 1}), env.radiance(direction_of(0.75, 0.5)));
}

TEST(Environment, BilinearAcrossTheSeamAndHeldAtThePoles) {
    const Environment env = numbered(8, 4);
    // u = 0 (and 1) lies halfway between the last column's centre and the first's.
    const Rgb seam = env.radiance(direction_of(0, (1 + 0.5) / 4));
    expect_rgb(seam, {3.5, 1, (1 + 7 + 8 + 1 + 0 + 8) / 2.0});
    // Above the top row's centres the lookup keeps the top row's values, interpolated along u.
    const Rgb near_pole = env.radiance(direction_of((2 + 0.75) / 8, 0.01));
    expect_rgb(near_pole, {2.25, 0, 3.25});
    const Rgb up = env.radiance({0, 1, 0}), down = env.radiance({0, -1, 0});
    EXPECT_EQ(up.y, 0);
    EXPECT_EQ(down.y, 3);
}

TEST(Environment, RotationTurnsItAboutUpFromXTowardMinusZ) {
    EnvironmentSettings turned;
    turned.rotation = 90;
    const Environment env = numbered(8, 4), rotated = numbered(8, 4, turned);
    expect_rgb(rotated.radiance({0, 0, -1}), env.radiance({1, 0, 0}));
    expect_rgb(rotated.radiance({1, 0, 0}), env.radiance({0, 0, 1}));
    EnvironmentSettings brighter;
    brighter.strength = 2.5;
    expect_rgb(numbered(8, 4, brighter).radiance({0.3, 0.2, 0.9}), env.radiance({0.3, 0.2, 0.9}) * 2.5);
}

// One bright texel among dim ones, turned a little: the distribution follows the texels.
Environment lopsided(int width, int height) {
    std::vector<float> rgb(size_t(width) * height * 3, 0.05f);
    for (int c = 0; c < 3; ++c) rgb[(size_t(1) * width + 5) * 3 + c] = 40;  // texel (5, 1)
    for (int c = 0; c < 3; ++c) rgb[(size_t(height - 1) * width) * 3 + c] = 0;  // a black texel
    EnvironmentSettings s;
    s.rotation = 33;
    return Environment(std::make_shared<const EnvironmentMap>(width, height, std::move(rgb)), s);
}

TEST(Environment, SampleReportsPdfsDensityWhichIntegratesToOne) {
    const Environment env = lopsided(16, 8);
    Rng rng(7, 0, 0);
    for (int n = 0; n < 2000; ++n) {
        Vec3 d;
        double pdf;
        ASSERT_TRUE(env.sample(rng.uniform(), rng.uniform(), d, pdf));
        EXPECT_NEAR(length(d), 1, 1e-12);
        EXPECT_NEAR(pdf, env.pdf(d), 1e-9 * pdf);
    }
    // ∫ pdf dω over a fine grid uniform in (φ, sin θ), whose points stand for equal solid angles.
    double sum = 0;
    const int columns = 4096, rows = 2048;
    for (int j = 0; j < rows; ++j)
        for (int i = 0; i < columns; ++i) {
            const double phi = 2 * kPi * (i + 0.5) / columns, z = -1 + 2 * (j + 0.5) / rows, r = std::sqrt(1 - z * z);
            sum += env.pdf({r * std::cos(phi), z, r * std::sin(phi)});
        }
    EXPECT_NEAR(sum * 4 * kPi / (double(columns) * rows), 1, 0.002);
}

// Pearson's χ² over the texels' cells the density reaches (none may fall elsewhere); the
// expected counts are the density times each cell's solid angle. The critical value at 0.1% for
// k - 1 degrees of freedom by Wilson and Hilferty's approximation (181.99 for 127: 181.95).
TEST(Environment, SamplesFallInEachCellAsTheDensitySays) {
    const int width = 16, height = 8;
    const Environment env = lopsided(width, height);
    const int n = 200000;
    std::vector<int> counts(size_t(width) * height, 0);
    const auto cell_of = [&](const Vec3& d) {
        // The cell in the image, undoing the rotation.
        double u = 0.5 + (std::atan2(d.z, d.x) + 33 * kPi / 180) / (2 * kPi);
        u -= std::floor(u);
        const double v = 0.5 - std::asin(std::clamp(d.y, -1.0, 1.0)) / kPi;
        return size_t(std::min(int(v * height), height - 1)) * width + std::min(int(u * width), width - 1);
    };
    Rng rng(11, 0, 0);
    for (int k = 0; k < n; ++k) {
        Vec3 d;
        double pdf;
        if (env.sample(rng.uniform(), rng.uniform(), d, pdf)) ++counts[cell_of(d)];
    }
    double chi2 = 0;
    int cells = 0;
    for (int j = 0; j < height; ++j) {
        const double top = std::sin(kPi * (0.5 - double(j) / height)), bottom = std::sin(kPi * (0.5 - double(j + 1) / height));
        const double solid_angle = 2 * kPi / width * (top - bottom);
        for (int i = 0; i < width; ++i) {
            const double phi = 2 * kPi * ((i + 0.5) / width - 0.5) - 33 * kPi / 180;
            const double theta = kPi * (0.5 - (j + 0.5) / height);
            const Vec3 centre{std::cos(theta) * std::cos(phi), std::sin(theta), std::cos(theta) * std::sin(phi)};
            const double expected = n * env.pdf(centre) * solid_angle;
            const int got = counts[size_t(j) * width + i];
            if (expected == 0) {
                EXPECT_EQ(got, 0) << i << ", " << j;
                continue;
            }
            ++cells;
            chi2 += (got - expected) * (got - expected) / expected;
        }
    }
    const double dof = cells - 1, h = 2 / (9 * dof);
    EXPECT_LT(chi2, dof * std::pow(1 - h + 3.0902 * std::sqrt(h), 3));
    // Compensation leaves out the cells below the mean: all but the bright texel's and its
    // neighbours' (whose bilinear lookups reach it).
    EXPECT_EQ(cells, 9);
}

// A uniform map has nothing above its mean: compensation leaves it whole.
TEST(Environment, CompensatingAUniformMapLeavesItWhole) {
    const Environment env(std::make_shared<const EnvironmentMap>(4, 2, std::vector<float>(4 * 2 * 3, 0.5f)), {});
    const Vec3 d = normalize(Vec3{0.2, 0.5, -0.7});
    EXPECT_NEAR(env.pdf(d), 1 / (4 * kPi), 1e-12);
}

TEST(Environment, ABlackEnvironmentSamplesNothing) {
    const Environment env(std::make_shared<const EnvironmentMap>(4, 2, std::vector<float>(4 * 2 * 3, 0.0f)), {});
    Vec3 d;
    double pdf;
    EXPECT_FALSE(env.sample(0.3, 0.6, d, pdf));
    EXPECT_EQ(env.pdf({0, 1, 0}), 0);
    EXPECT_EQ(env.luminance_integral(), 0);
}

TEST(Environment, RefusesAnImageOfTheWrongSize) {
    EXPECT_THROW(EnvironmentMap(4, 2, std::vector<float>(5)), std::invalid_argument);
    EXPECT_THROW(EnvironmentMap(0, 2, {}), std::invalid_argument);
    EXPECT_THROW(Environment(nullptr, {}), std::invalid_argument);
}

}  // namespace
}  // namespace glint
