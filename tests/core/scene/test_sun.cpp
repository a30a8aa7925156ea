// The sun's sampling: directions fill its cone as the density it reports says (Pearson's χ²
// over equal-solid-angle cells of the cone), the density integrates to one over the cone and is
// zero outside it, and a delta sun gives its own direction and irradiance.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "base/rng.h"
#include "scene/sun.h"

namespace glint {
namespace {

SunSettings wide_sun() {
    SunSettings s;
    s.direction = normalize(Vec3{-0.4, 0.8, 0.3});
    s.irradiance = Rgb{2, 3, 4};
    s.angle = 30;  // wide enough that cells of the cone are many sample spacings across
    return s;
}

TEST(Sun, SamplesFillTheConeAsTheDensitySays) {
    const Sun sun(wide_sun());
    const Frame frame = Frame::around(sun.settings().direction);
    const double one_minus_cos_max = 1 - std::cos(15 * kPi / 180);
    // 8 rings of equal solid angle (equal steps of cos θ) × 8 sectors: 64 cells, 63 degrees of
    // freedom, whose 0.1% critical value is 103.44.
    const int rings = 8, sectors = 8, n = 100000;
    std::vector<int> counts(rings * sectors, 0);
    Rng rng(5, 0, 0);
    for (int k = 0; k < n; ++k) {
        Vec3 d;
        Rgb value;
        double pdf;
        sun.sample(rng.uniform(), rng.uniform(), d, value, pdf);
        ASSERT_NEAR(length(d), 1, 1e-12);
        ASSERT_EQ(pdf, sun.pdf(d));
        const Vec3 local = frame.to_local(d);
        const double x = (1 - local.z) / one_minus_cos_max;  // 0 at the centre, 1 at the rim
        ASSERT_LE(x, 1 + 1e-9);
        double phi = std::atan2(local.y, local.x) / (2 * kPi);
        phi -= std::floor(phi);
        ++counts[std::min(int(x * rings), rings - 1) * sectors + std::min(int(phi * sectors), sectors - 1)];
    }
    double chi2 = 0;
    const double expected = double(n) / (rings * sectors);
    for (int c : counts) chi2 += (c - expected) * (c - expected) / expected;
    EXPECT_LT(chi2, 103.44);
    // The density times the cone's solid angle is one; none outside the cone.
    EXPECT_NEAR(sun.pdf(sun.settings().direction) * 2 * kPi * one_minus_cos_max, 1, 1e-9);
    EXPECT_EQ(sun.pdf(frame.to_world({std::sin(16 * kPi / 180), 0, std::cos(16 * kPi / 180)})), 0);
    // The radiance over the disc gives the irradiance on a facing surface: L·π·sin²α.
    const Rgb l = sun.radiance(sun.settings().direction);
    EXPECT_NEAR(l.z * kPi * std::pow(std::sin(15 * kPi / 180), 2), 4, 1e-9);
}

TEST(Sun, ADeltaSunGivesItsDirectionAndIrradiance) {
    SunSettings s = wide_sun();
    s.angle = 0;
    const Sun sun(s);
    Vec3 d;
    Rgb value;
    double pdf;
    sun.sample(0.3, 0.7, d, value, pdf);
    EXPECT_EQ(d, s.direction);
    EXPECT_EQ(value, s.irradiance);
    EXPECT_EQ(pdf, 1);
    EXPECT_EQ(sun.pdf(s.direction), 0);  // no direction found by chance reaches it
    EXPECT_EQ(sun.radiance(s.direction).y, 0);
}

}  // namespace
}  // namespace glint
