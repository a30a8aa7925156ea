// Every BSDF against its own claims, over roughnesses and incident angles up to grazing: sample()
// draws directions with the density pdf() states (a χ² test, as pbrt-v4's BSDF tests), its
// weight is evaluate()'s f·|cos| / pdf, reflection is reciprocal (transmission as η² says), no
// value is NaN, infinite or negative, and no energy is created.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "base/sampling.h"
#include "scene/bsdf.h"
#include "scene/fresnel.h"

namespace glint {
namespace {

const Vec3 kUp{0, 0, 1};  // the outward normal

// The direction back toward where a path came from, `degrees` from the normal, above or below.
Vec3 wo_at(double degrees, bool above = true) {
    const double a = degrees * kPi / 180;
    return {std::sin(a), 0, above ? std::cos(a) : -std::cos(a)};
}

struct Case {
    std::string name;
    Material m;
};

Material make(MaterialType type, double roughness, double albedo = 1) {
    Material m = default_material(type);
    m.roughness = roughness;
    m.albedo = Rgb{albedo};
    return m;
}

Material glass(double roughness, FresnelModel fresnel, double ior = 1.5) {
    Material m = make(MaterialType::glass, roughness);
    m.fresnel = fresnel;
    m.ior = ior;
    return m;
}

Material plastic(double roughness, double metallic, Rgb albedo = {0.8, 0.5, 0.2}) {
    Material m = make(MaterialType::plastic, roughness);
    m.albedo = albedo;
    m.metallic = metallic;
    return m;
}

// The BSDFs with a non-specular part, at roughnesses whose lobes a 9° grid resolves.
std::vector<Case> resolvable_cases() {
    return {{"diffuse", make(MaterialType::diffuse, 0, 0.8)},
            {"mirror 0.3", make(MaterialType::mirror, 0.3)},
            {"mirror 1", make(MaterialType::mirror, 1)},
            {"metal 0.5", make(MaterialType::metal, 0.5, 0.9)},
            {"glass 0.4 schlick", glass(0.4, FresnelModel::schlick)},
            {"glass 0.6 exact", glass(0.6, FresnelModel::exact)},
            {"glass 1 exact", glass(1, FresnelModel::exact)},
            {"glass 0.5 ior 0.7", glass(0.5, FresnelModel::exact, 0.7)},
            {"plastic 0 (delta coat)", plastic(0, 0)},
            {"plastic 0.4", plastic(0.4, 0)},
            {"plastic 0.7 metallic 0.5", plastic(0.7, 0.5)}};
}

// Every material at every roughness the sweep covers, the threshold's neighbours included.
std::vector<Case> all_cases() {
    std::vector<Case> cases{{"diffuse", make(MaterialType::diffuse, 0, 0.8)}};
    for (double r : {0.0, 1e-4, 0.0316, 0.0317, 0.1, 0.25, 0.5, 1.0}) {
        const std::string at = " r=" + std::to_string(r);
        cases.push_back({"mirror" + at, make(MaterialType::mirror, r)});
        cases.push_back({"metal" + at, make(MaterialType::metal, r, 0.9)});
        cases.push_back({"plastic" + at, plastic(r, 0)});
        cases.push_back({"plastic metallic 0.5" + at, plastic(r, 0.5)});
        cases.push_back({"glass schlick" + at, glass(r, FresnelModel::schlick)});
        cases.push_back({"glass exact" + at, glass(r, FresnelModel::exact)});
        cases.push_back({"glass ior 0.7" + at, glass(r, FresnelModel::exact, 0.7)});
    }
    return cases;
}

// The upper regularised incomplete gamma function's tail for χ², by the Wilson-Hilferty
// normal approximation (good to ~1e-3 in p for more than 30 degrees of freedom).
double chi2_p_value(double chi2, int dof) {
    const double k = dof, z = (std::cbrt(chi2 / k) - (1 - 2 / (9 * k))) / std::sqrt(2 / (9 * k));
    return 0.5 * std::erfc(z / std::sqrt(2.0));
}

constexpr int kThetaBins = 20, kPhiBins = 40;

int bin_of(const Vec3& w) {
    const double theta = std::acos(std::clamp(w.z, -1.0, 1.0));
    double phi = std::atan2(w.y, w.x);
    if (phi < 0) phi += 2 * kPi;
    const int i = std::min(kThetaBins - 1, int(theta / kPi * kThetaBins));
    const int j = std::min(kPhiBins - 1, int(phi / (2 * kPi) * kPhiBins));
    return i * kPhiBins + j;
}

// ∫ pdf over each bin, by the midpoint rule on 16 × 24 cells: lobes near grazing are narrow in φ,
// and refraction's critical angle puts an edge in θ.
std::vector<double> integrated_pdf(const Bsdf& bsdf, const Vec3& wo) {
    std::vector<double> out(kThetaBins * kPhiBins, 0.0);
    constexpr int kSubTheta = 16, kSubPhi = 24;
    const double dt = kPi / kThetaBins / kSubTheta, dp = 2 * kPi / kPhiBins / kSubPhi;
    for (int i = 0; i < kThetaBins * kSubTheta; ++i)
        for (int j = 0; j < kPhiBins * kSubPhi; ++j) {
            const double theta = (i + 0.5) * dt, phi = (j + 0.5) * dp;
            const Vec3 w{std::sin(theta) * std::cos(phi), std::sin(theta) * std::sin(phi), std::cos(theta)};
            out[size_t((i / kSubTheta) * kPhiBins + j / kSubPhi)] += bsdf.pdf(wo, w) * std::sin(theta) * dt * dp;
        }
    return out;
}

TEST(Bsdf, SamplesFollowTheStatedDensityChiSquared) {
    constexpr int kSamples = 100000;
    const std::vector<Case> cases = resolvable_cases();
    const std::vector<double> angles{0, 30, 60, 85};
    const double threshold = 0.01 / double(cases.size() * angles.size() * 2);  // Šidák-like correction
    uint64_t key = 0;
    for (const Case& c : cases)
        for (double angle : angles)
            for (bool above : {true, false}) {
                const Bsdf bsdf(c.m, kUp);
                const Vec3 wo = wo_at(angle, above);
                Rng rng(41, ++key, 0);
                std::vector<double> observed(kThetaBins * kPhiBins, 0.0);
                for (int s = 0; s < kSamples; ++s) {
                    const BsdfSample b = bsdf.sample(wo, rng);
                    if (b.pdf > 0 && !is_black(b.weight)) observed[size_t(bin_of(b.wi))] += 1;
                }
                const std::vector<double> expected_pdf = integrated_pdf(bsdf, wo);
                // Pool bins expecting fewer than 5 samples into one.
                double chi2 = 0, pooled_observed = 0, pooled_expected = 0;
                int dof = 0;
                for (size_t b = 0; b < observed.size(); ++b) {
                    const double e = expected_pdf[b] * kSamples;
                    if (e < 5) {
                        pooled_observed += observed[b];
                        pooled_expected += e;
                        continue;
                    }
                    chi2 += (observed[b] - e) * (observed[b] - e) / e;
                    ++dof;
                }
                if (pooled_expected > 5) {
                    chi2 += (pooled_observed - pooled_expected) * (pooled_observed - pooled_expected) / pooled_expected;
                    ++dof;
                } else {
                    EXPECT_LT(pooled_observed, 25) << c.name << " at " << angle;
                }
                if (dof < 2) continue;  // all its mass in a delta lobe from here
                const double p = chi2_p_value(chi2, dof - 1);
                EXPECT_GT(p, threshold) << c.name << " at " << angle << (above ? " above" : " below") << ": χ² "
                                        << chi2 << " with " << dof - 1 << " degrees of freedom";
            }
}

TEST(Bsdf, EachSamplesWeightIsEvalOverPdf) {
    uint64_t key = 0;
    for (const Case& c : all_cases())
        for (double angle : {0.0, 45.0, 80.0, 89.9})
            for (bool above : {true, false}) {
                const Bsdf bsdf(c.m, kUp);
                const Vec3 wo = wo_at(angle, above);
                Rng rng(42, ++key, 0);
                for (int s = 0; s < 2000; ++s) {
                    const BsdfSample b = bsdf.sample(wo, rng);
                    if (is_black(b.weight)) continue;
                    EXPECT_NEAR(length(b.wi), 1, 1e-9) << c.name;
                    if (b.is_specular()) {
                        EXPECT_EQ(b.pdf, 0) << c.name;
                        continue;
                    }
                    const BsdfValue v = bsdf.evaluate(wo, b.wi);
                    ASSERT_GT(v.pdf, 0) << c.name << " at " << angle;
                    EXPECT_NEAR(v.pdf / b.pdf, 1, 1e-9) << c.name << " at " << angle;
                    for (int k = 0; k < 3; ++k)
                        EXPECT_NEAR(b.weight[k], v.f_cos[k] / v.pdf, 1e-9 * (1 + b.weight[k])) << c.name << " at " << angle;
                }
            }
}

TEST(Bsdf, ReflectionIsReciprocalAndTransmissionScalesByEtaSquared) {
    Rng rng(43, 0, 0);
    for (const Case& c : resolvable_cases()) {
        const Bsdf bsdf(c.m, kUp);
        int checked = 0;
        for (int s = 0; s < 20000; ++s) {
            const Vec3 a = sample_uniform_sphere(rng.uniform(), rng.uniform());
            const Vec3 b = sample_uniform_sphere(rng.uniform(), rng.uniform());
            const double f_ab = bsdf.eval(a, b).x / std::fabs(b.z), f_ba = bsdf.eval(b, a).x / std::fabs(a.z);
            if (!(f_ab > 1e-6)) continue;
            ++checked;
            double scale = 1;  // f(b, a) = f(a, b)·(η_a/η_b)² across the surface
            if (a.z * b.z < 0) {
                const double ior = c.m.ior;
                scale = a.z > 0 ? 1 / (ior * ior) : ior * ior;
            }
            EXPECT_NEAR(f_ba / (f_ab * scale), 1, 1e-8) << c.name << " a " << a.z << " b " << b.z;
        }
        EXPECT_GT(checked, 1000) << c.name;
    }
}

// ∫ f·|cos θi| dωi over the sphere by the midpoint rule in (θ, φ), finely in φ: lobes near
// grazing are narrow there.
double integrated_reflectance(const Bsdf& bsdf, const Vec3& wo) {
    constexpr int kTheta = 600, kPhi = 1600;
    const double dt = kPi / kTheta, dp = 2 * kPi / kPhi;
    double sum = 0;
    for (int i = 0; i < kTheta; ++i)
        for (int j = 0; j < kPhi; ++j) {
            const double theta = (i + 0.5) * dt, phi = (j + 0.5) * dp;
            sum += bsdf.eval(wo, {std::sin(theta) * std::cos(phi), std::sin(theta) * std::sin(phi), std::cos(theta)}).x *
                   std::sin(theta);
        }
    return sum * dt * dp;
}

// GGX's formulas written out here afresh, for single scattering seen from o (o.z > 0): the
// expectation over visible normals h of what `scatter(h)` keeps, ∫ D(h)·G1(o)·max(0, o·h) / o.z
// · scatter(h) dωh, by the midpoint rule in (θh, φh).
template <typename Scatter>
double over_visible_normals(double alpha, const Vec3& o, Scatter scatter) {
    const double a2 = alpha * alpha;
    const auto g1 = [a2](const Vec3& w) { return 2 / (1 + std::sqrt(1 + a2 * (w.x * w.x + w.y * w.y) / (w.z * w.z))); };
    constexpr int kTheta = 1000, kPhi = 400;
    const double dt = 0.5 * kPi / kTheta, dp = 2 * kPi / kPhi;
    double sum = 0;
    for (int i = 0; i < kTheta; ++i)
        for (int j = 0; j < kPhi; ++j) {
            const double theta = (i + 0.5) * dt, phi = (j + 0.5) * dp;
            const Vec3 h{std::sin(theta) * std::cos(phi), std::sin(theta) * std::sin(phi), std::cos(theta)};
            const double c = dot(o, h);
            if (!(c > 0)) continue;
            const double tan2 = std::tan(theta) * std::tan(theta), e = 1 + tan2 / a2;
            const double d = 1 / (kPi * a2 * std::pow(h.z, 4) * e * e);
            sum += d * g1(o) * c / o.z * scatter(h, c, g1) * std::sin(theta);
        }
    return sum * dt * dp;
}

// GGX's single-scattering albedo: the reflection about h kept where it leaves above the surface.
double ggx_albedo(double alpha, const Vec3& o) {
    return over_visible_normals(alpha, o, [&o](const Vec3& h, double c, auto g1) {
        const Vec3 r = h * (2 * c) - o;
        return r.z > 0 ? g1(r) : 0.0;
    });
}

// Rough glass's single scattering with exact Fresnel: reflection with F, refraction with 1 - F,
// each kept where it leaves on its own side; eta the near index over the far one.
double glass_albedo(double alpha, double eta, const Vec3& o) {
    return over_visible_normals(alpha, o, [&o, eta](const Vec3& h, double c, auto g1) {
        const Vec3 r = h * (2 * c) - o;
        const double kept_r = r.z > 0 ? g1(r) : 0.0, sin2_t = eta * eta * (1 - c * c);
        if (sin2_t >= 1) return kept_r;
        const double cos_t = std::sqrt(1 - sin2_t), n = 1 / eta;  // far over near
        const double rs = (c - n * cos_t) / (c + n * cos_t), rp = (n * c - cos_t) / (n * c + cos_t);
        const double f = 0.5 * (rs * rs + rp * rp);
        const Vec3 t = o * -eta + h * (eta * c - cos_t);
        return f * kept_r + (1 - f) * (t.z < 0 ? g1(t) : 0.0);
    });
}

double mean_weight(const Bsdf& bsdf, const Vec3& wo, uint64_t key, double& sigma) {
    Rng rng(44, key, 0);
    constexpr int kSamples = 200000;
    double sum = 0, sum_sq = 0;
    for (int s = 0; s < kSamples; ++s) {
        const double w = bsdf.sample(wo, rng).weight.x;
        sum += w;
        sum_sq += w * w;
    }
    const double mean = sum / kSamples;
    sigma = std::sqrt(std::max(0.0, sum_sq / kSamples - mean * mean) / kSamples);
    return mean;
}

TEST(Bsdf, WhiteFurnaceRoughMirrorReturnsGgxsSingleScatteringAlbedo) {
    uint64_t key = 0;
    for (double r : {0.3, 0.6, 1.0})
        for (double angle : {0.0, 60.0, 85.0}) {
            const Material mirror = make(MaterialType::mirror, r), metal = make(MaterialType::metal, r);
            const Vec3 wo = wo_at(angle);
            const double expected = ggx_albedo(r * r, wo);
            EXPECT_LE(expected, 1);
            for (const Material& m : {mirror, metal}) {  // metal of albedo 1: F = 1 everywhere
                double sigma;
                const double mean = mean_weight(Bsdf(m, kUp), wo, ++key, sigma);
                EXPECT_NEAR(mean, expected, 4 * sigma + 2e-3) << "r " << r << " at " << angle;
                EXPECT_NEAR(integrated_reflectance(Bsdf(m, kUp), wo), expected, 3e-3) << "r " << r << " at " << angle;
            }
        }
    // Smoother surfaces lose less: at r = 0.3 and normal incidence, under 1%.
    EXPECT_GT(ggx_albedo(0.09, wo_at(0)), 0.99);
}

TEST(Bsdf, RoughGlassKeepsWhatSingleScatteringDoesNotLose) {
    uint64_t key = 0;
    for (double r : {0.3, 0.6, 1.0})
        for (double angle : {0.0, 60.0, 85.0})
            for (bool above : {true, false}) {
                const Material m = glass(r, FresnelModel::exact);
                const Bsdf bsdf(m, kUp);
                const Vec3 wo = wo_at(angle, above);
                // Reflected plus transmitted: 1 less the single-scattering loss.
                const double expected = glass_albedo(r * r, above ? 1 / 1.5 : 1.5, wo_at(angle));
                EXPECT_LE(expected, 1);
                double sigma;
                const double sampled = mean_weight(bsdf, wo, ++key, sigma);
                const std::string at = std::to_string(r) + " at " + std::to_string(angle) + (above ? " above" : " below");
                EXPECT_NEAR(sampled, expected, 4 * sigma + 2e-3) << at;
                EXPECT_NEAR(integrated_reflectance(bsdf, wo), expected, 3e-3) << at;
            }
    EXPECT_GT(glass_albedo(0.09, 1 / 1.5, wo_at(0)), 0.99);  // smooth glass loses almost nothing
}

TEST(Bsdf, PlasticAndMetalNeverCreateEnergy) {
    uint64_t key = 0;
    for (double r : {0.0, 0.1, 0.5, 1.0})
        for (double metallic : {0.0, 0.5, 1.0})
            for (double angle : {0.0, 60.0, 89.9}) {
                const Material m = plastic(r, metallic, Rgb{1});
                const Bsdf bsdf(m, kUp);
                double sigma;
                const double mean = mean_weight(bsdf, wo_at(angle), ++key, sigma);
                EXPECT_LE(mean, 1 + 4 * sigma) << r << " " << metallic;
            }
}

TEST(Bsdf, NoNanInfOrNegativeAtAnyRoughnessOrAngle) {
    uint64_t key = 0;
    for (const Case& c : all_cases())
        for (double angle : {0.0, 1e-9, 30.0, 89.0, 89.9, 89.999, 90.0})
            for (bool above : {true, false}) {
                const Bsdf bsdf(c.m, kUp);
                const Vec3 wo = wo_at(angle, above);
                Rng rng(45, ++key, 0);
                for (int s = 0; s < 500; ++s) {
                    const BsdfSample b = bsdf.sample(wo, rng);
                    ASSERT_TRUE(is_finite(b.weight) && is_finite(b.wi) && std::isfinite(b.pdf)) << c.name << " " << angle;
                    EXPECT_GE(min_component(b.weight), 0) << c.name;
                    EXPECT_GE(b.pdf, 0) << c.name;
                    const Vec3 wi = sample_uniform_sphere(rng.uniform(), rng.uniform());
                    const BsdfValue v = bsdf.evaluate(wo, wi);
                    ASSERT_TRUE(is_finite(v.f_cos) && std::isfinite(v.pdf)) << c.name << " " << angle;
                    EXPECT_GE(min_component(v.f_cos), 0) << c.name;
                    EXPECT_GE(v.pdf, 0) << c.name;
                }
            }
}

TEST(Bsdf, ReflectionOnlyBsdfsNeverSendLightThroughTheSurface) {
    Rng rng(46, 0, 0);
    for (const Case& c : all_cases()) {
        if (Bsdf::flags(c.m).has(BsdfFlags::transmission)) continue;
        const Bsdf bsdf(c.m, kUp);
        for (bool above : {true, false})
            for (double angle : {0.0, 70.0, 89.99}) {
                const Vec3 wo = wo_at(angle, above);
                for (int s = 0; s < 500; ++s) {
                    const BsdfSample b = bsdf.sample(wo, rng);
                    if (!is_black(b.weight)) {
                        EXPECT_GT(b.wi.z * wo.z, 0) << c.name;
                    }
                    // Nothing arrives from the other side.
                    const Vec3 through{rng.uniform() - 0.5, rng.uniform() - 0.5, above ? -1.0 : 1.0};
                    EXPECT_TRUE(is_black(bsdf.eval(wo, normalize(through)))) << c.name;
                }
            }
    }
}

TEST(Bsdf, FlagsSayWhichStrategiesApply) {
    EXPECT_TRUE(Bsdf::flags(make(MaterialType::diffuse, 0)).is_diffuse());
    for (MaterialType t : {MaterialType::mirror, MaterialType::glass, MaterialType::metal}) {
        EXPECT_TRUE(Bsdf::flags(make(t, 0)).is_specular());
        EXPECT_TRUE(Bsdf::flags(make(t, 1e-4)).is_specular());  // below the threshold: handled as smooth
        const BsdfFlags rough = Bsdf::flags(make(t, 0.2));
        EXPECT_FALSE(rough.is_specular() || rough.is_diffuse());
        EXPECT_TRUE(rough.has(BsdfFlags::glossy));
    }
    EXPECT_TRUE(Bsdf::flags(glass(0, FresnelModel::exact)).has(BsdfFlags::transmission));
    EXPECT_FALSE(Bsdf::flags(make(MaterialType::mirror, 0.5)).has(BsdfFlags::transmission));
    // A smooth coat over a diffuse base is neither: light sampling applies, light paths do not.
    const BsdfFlags coat = Bsdf::flags(plastic(0, 0));
    EXPECT_TRUE(coat.has(BsdfFlags::specular) && coat.has(BsdfFlags::diffuse));
    EXPECT_FALSE(coat.is_specular() || coat.is_diffuse());
}

TEST(Bsdf, ExactFresnelMeetsItsKnownValues) {
    // Normal incidence: ((n - 1)/(n + 1))²; total reflection beyond the critical angle.
    EXPECT_NEAR(fresnel_dielectric(1, 1.5), 0.04, 1e-15);
    EXPECT_EQ(fresnel_dielectric(std::cos(42 * kPi / 180), 1 / 1.5), 1);
    // At Brewster's angle the parallel part vanishes: F = r_perp² / 2.
    const double brewster = std::atan(1.5), ci = std::cos(brewster), ct = std::sin(brewster);
    const double perp = (ci - 1.5 * ct) / (ci + 1.5 * ct);
    EXPECT_NEAR(fresnel_dielectric(ci, 1.5), 0.5 * perp * perp, 1e-15);
}

}  // namespace
}  // namespace glint
