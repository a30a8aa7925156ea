// Materials: total internal reflection, grazing incidence, Snell's law, and no energy created.
#include <gtest/gtest.h>

#include "scene/bsdf.h"
#include "base/sampling.h"

namespace glint {
namespace {

const Vec3 kUp{0, 0, 1};  // outward normal of the surface

Vec3 incoming_at(double degrees_from_normal, bool from_outside) {
    const double a = degrees_from_normal * kPi / 180;
    const Vec3 d{std::sin(a), 0, -std::cos(a)};
    return from_outside ? d : Vec3{d.x, d.y, -d.z};
}

Material glass(double albedo = 1) { return {MaterialType::glass, Rgb{albedo}, 1.5, Rgb{0}}; }
const Material kGlass = glass(), kTintedGlass = glass(0.9);

TEST(Materials, TotalInternalReflectionAlwaysReflects) {
    Rng rng(31, 0, 0);
    // From inside n = 1.5 the critical angle is asin(1/1.5) = 41.8°.
    for (double angle : {42.0, 60.0, 89.9}) {
        const Vec3 d = incoming_at(angle, false);
        for (int i = 0; i < 1000; ++i) {
            const BsdfSample s = Bsdf(kTintedGlass, kUp).sample(-d, rng);
            EXPECT_TRUE(s.is_specular());
            EXPECT_NEAR(s.wi.z, -d.z, 1e-12);  // mirrored back inside
            EXPECT_NEAR(s.wi.x, d.x, 1e-12);
            EXPECT_EQ(s.weight, Rgb{0.9});
        }
    }
}

TEST(Materials, GlassObeysSnellAndConservesEnergyAtEveryAngle) {
    Rng rng(32, 0, 0);
    for (bool outside : {true, false}) {
        for (double angle : {0.0, 30.0, 41.0, 80.0, 89.99}) {
            const Vec3 d = incoming_at(angle, outside);
            double sum = 0, sum_sq = 0;
            const int n = 20000;
            for (int i = 0; i < n; ++i) {
                const BsdfSample s = Bsdf(kGlass, kUp).sample(-d, rng);
                ASSERT_TRUE(is_finite(s.weight));
                EXPECT_NEAR(length(s.wi), 1, 1e-12);
                const bool refracted = (s.wi.z < 0) == outside;
                if (refracted) {
                    const double eta = outside ? 1 / 1.5 : 1.5;
                    EXPECT_NEAR(std::sqrt(1 - s.wi.z * s.wi.z), eta * std::sin(angle * kPi / 180), 1e-9);
                }
                sum += s.weight.x;
                sum_sq += s.weight.x * s.weight.x;
            }
            // Re/P and Tr/(1-P) average to Re + Tr = 1: lossless, never more.
            const double mean = sum / n, sigma = std::sqrt((sum_sq / n - mean * mean) / n);
            EXPECT_NEAR(mean, 1, 3 * sigma + 1e-12) << "angle " << angle << (outside ? " outside" : " inside");
        }
    }
}

TEST(Materials, SplitGlassFollowsBothDirectionsWithFresnelWeightsThatSumToTheAlbedo) {
    Rng rng(34, 0, 0);
    for (bool outside : {true, false})
        for (double angle : {0.0, 30.0, 41.0, 80.0}) {
            const Vec3 d = incoming_at(angle, outside);
            BsdfSample reflected, refracted;
            const bool split = Bsdf(kTintedGlass, kUp).split(-d, reflected, refracted);
            ASSERT_EQ(split, outside || angle < 41.5) << angle;  // beyond ~41.8° inside: total reflection
            if (!split) continue;
            EXPECT_NEAR(reflected.weight.x + refracted.weight.x, 0.9, 1e-15) << angle;
            EXPECT_GT(refracted.weight.x, reflected.weight.x) << angle;
            // The directions are the two that sampling picks between.
            for (int i = 0; i < 64; ++i) {
                const BsdfSample s = Bsdf(kTintedGlass, kUp).sample(-d, rng);
                EXPECT_TRUE(s.wi == reflected.wi || s.wi == refracted.wi) << angle;
            }
        }
}

TEST(Materials, GrazingIncidenceOnGlassMostlyReflects) {
    Rng rng(33, 0, 0);
    const Vec3 d = incoming_at(89.999, true);
    int reflected = 0;
    for (int i = 0; i < 10000; ++i) reflected += Bsdf(kGlass, kUp).sample(-d, rng).wi.z > 0;
    // Schlick's Re is ~1 at grazing, so P = 1/4 + Re/2 is ~3/4.
    EXPECT_NEAR(reflected / 10000.0, 0.75, 0.02);
}

TEST(Materials, DiffuseAndMirrorNeverCreateEnergy) {
    Rng rng(34, 0, 0);
    const Material white{MaterialType::diffuse, Rgb{1}, 1.5, Rgb{0}};
    const Material mirror{MaterialType::mirror, Rgb{1}, 1.5, Rgb{0}};
    for (double angle : {0.0, 45.0, 89.9}) {
        for (bool outside : {true, false}) {
            const Vec3 d = incoming_at(angle, outside);
            for (int i = 0; i < 1000; ++i) {
                const BsdfSample s = Bsdf(white, kUp).sample(-d, rng);
                EXPECT_LE(max_component(s.weight), 1.0);
                EXPECT_GT(-dot(s.wi, kUp) * dot(d, kUp), -1e-15);  // back to the side it came from
                const BsdfValue f = Bsdf(white, kUp).evaluate(-d, s.wi);
                EXPECT_NEAR(f.pdf, s.pdf, 1e-12);
                EXPECT_NEAR(f.f_cos.x / f.pdf, 1, 1e-12);
                const BsdfSample m = Bsdf(mirror, kUp).sample(-d, rng);
                EXPECT_EQ(m.weight, Rgb{1});
                EXPECT_NEAR(m.wi.z, -d.z, 1e-15);
            }
        }
    }
}

TEST(Materials, DiffuseSeesNothingBehindTheSurface) {
    const Material white{MaterialType::diffuse, Rgb{1}, 1.5, Rgb{0}};
    const BsdfValue f = Bsdf(white, kUp).evaluate(-incoming_at(30, true), {0, 0, -1});
    EXPECT_TRUE(is_black(f.f_cos));
    EXPECT_EQ(f.pdf, 0);
}

}  // namespace
}  // namespace glint
