// The path guide (render/path_guide.h, guide_quadtree.h, guided_bsdf.h): its distributions are
// densities that sample() draws from, what it learns does not depend on the order of its
// records, the mixture's weights make an unbiased estimate, and a guided render converges to the
// unguided image with an honest error estimate, bit-identical for any thread count.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <sstream>
#include <thread>

#include <nlohmann/json.hpp>

#include "base/sampling.h"
#include "io/image_io.h"
#include "render/guided_bsdf.h"
#include "render/path_guide.h"
#include "support/test_support.h"

namespace glint {
namespace {

// A quadtree that learned light from around direction d (a cone of cos 0.9) and a little from
// everywhere: the shape guiding sees under a small bright window.
GuideQuadtree learned_from_cone(const Vec3& d, int iterations = 2) {
    GuideQuadtree tree;
    Rng rng(1, 2, 3);
    for (int it = 0; it < iterations; ++it) {
        for (int i = 0; i < 20000; ++i) {
            const Vec3 w = sample_uniform_sphere(rng.uniform(), rng.uniform());
            tree.record(direction_to_square(w), dot(w, d) > 0.9 ? 100.0 : 1.0);
        }
        tree.learn_and_refine(0.01, 20);
    }
    return tree;
}

TEST(GuideQuadtree, TheSquareMapsDirectionsBothWays) {
    Rng rng(7, 0, 0);
    for (int i = 0; i < 1000; ++i) {
        const Vec3 w = sample_uniform_sphere(rng.uniform(), rng.uniform());
        const Vec3 back = square_to_direction(direction_to_square(w));
        EXPECT_LT(length(back - w), 1e-12);
    }
}

// The learned density integrates to one over the square and is what sample() reports; samples
// land in the bright cone at the rate the density gives it.
TEST(GuideQuadtree, SamplesItsOwnDensity) {
    const Vec3 d = normalize(Vec3{1, 2, -1});
    const GuideQuadtree tree = learned_from_cone(d);
    ASSERT_TRUE(tree.learned());
    EXPECT_GT(tree.nodes(), 20u);
    const int n = 512;
    double integral = 0;
    for (int i = 0; i < n; ++i)
        for (int j = 0; j < n; ++j) integral += tree.pdf({(i + 0.5) / n, (j + 0.5) / n}) / (double(n) * n);
    EXPECT_NEAR(integral, 1, 1e-3);
    Rng rng(9, 0, 0);
    int in_cone = 0;
    double expected = 0;
    const int samples = 100000;
    for (int i = 0; i < samples; ++i) {
        double pdf;
        const SquarePoint s = tree.sample(rng.uniform(), rng.uniform(), pdf);
        ASSERT_NEAR(pdf, tree.pdf(s), 1e-9 * pdf);
        in_cone += dot(square_to_direction(s), d) > 0.9;
    }
    for (int i = 0; i < n; ++i)
        for (int j = 0; j < n; ++j) {
            const SquarePoint s{(i + 0.5) / n, (j + 0.5) / n};
            if (dot(square_to_direction(s), d) > 0.9) expected += tree.pdf(s) / (double(n) * n);
        }
    // The cone holds 5% of the sphere and 84% of the light: the guide puts most samples there.
    EXPECT_GT(expected, 0.7);
    EXPECT_NEAR(in_cone / double(samples), expected, 5 * std::sqrt(expected * (1 - expected) / samples) + 0.01);
}

// Records from two threads in any interleaving, or from one in another order, learn the same.
TEST(GuideQuadtree, LearnsTheSameWhateverTheOrderOfRecords) {
    std::vector<std::pair<SquarePoint, double>> records;
    Rng rng(3, 0, 0);
    for (int i = 0; i < 40000; ++i) records.push_back({{rng.uniform(), rng.uniform()}, 1e3 * rng.uniform() * rng.uniform()});
    GuideQuadtree one, two;
    for (auto it = records.rbegin(); it != records.rend(); ++it) one.record(it->first, it->second);
    std::thread a([&] { for (size_t i = 0; i < records.size(); i += 2) two.record(records[i].first, records[i].second); });
    std::thread b([&] { for (size_t i = 1; i < records.size(); i += 2) two.record(records[i].first, records[i].second); });
    a.join();
    b.join();
    one.learn_and_refine(0.01, 20);
    two.learn_and_refine(0.01, 20);
    ASSERT_EQ(one.nodes(), two.nodes());
    for (int i = 0; i < 1000; ++i) {
        const SquarePoint s{rng.uniform(), rng.uniform()};
        EXPECT_EQ(one.pdf(s), two.pdf(s));
    }
}

TEST(ExactSum, CarriesPastSixtyFourBits) {
    ExactSum sum;
    for (int i = 0; i < 8; ++i) sum.add(uint64_t(1) << 62);
    EXPECT_EQ(sum.hi, 2u);
    EXPECT_EQ(sum.lo, 0u);
    EXPECT_EQ(sum.value(), std::ldexp(2.0, 64 - GuideQuadtree::kFractionBits));
}

// A leaf that records more than its share splits; each half then learns its own light.
TEST(PathGuide, SplitsWhereRecordsCrowdAndLearnsEachRegionApart) {
    Bounds3 box;
    box.extend(Vec3{-1, -1, -1});
    box.extend(Vec3{1, 1, 1});
    PathGuide guide(box);
    EXPECT_EQ(guide.at(Vec3{0, 0, 0}), nullptr);
    Rng rng(5, 0, 0);
    const Vec3 up{0, 1, 0}, down{0, -1, 0};
    for (int it = 0; it < 3; ++it) {
        for (int i = 0; i < 200000; ++i) {
            const Vec3 p{2 * rng.uniform() - 1, 2 * rng.uniform() - 1, 2 * rng.uniform() - 1};
            const Vec3 w = sample_uniform_sphere(rng.uniform(), rng.uniform());
            guide.record(p, w, dot(w, p.x < 0 ? up : down) > 0.9 ? 50.0 : 1.0);
        }
        guide.learn(200000);
    }
    EXPECT_GT(guide.stats().leaves, 8u);
    const GuideQuadtree* left = guide.at(Vec3{-0.5, 0, 0});
    const GuideQuadtree* right = guide.at(Vec3{0.5, 0, 0});
    ASSERT_NE(left, nullptr);
    ASSERT_NE(right, nullptr);
    EXPECT_GT(left->pdf(direction_to_square(up)), 5 * left->pdf(direction_to_square(down)));
    EXPECT_GT(right->pdf(direction_to_square(down)), 5 * right->pdf(direction_to_square(up)));
}

// The mixture's sample weight is f·cos over the density evaluate() gives the same direction,
// and that density integrates to one over the sphere (the BSDF's share to 1 - α).
TEST(GuidedBsdf, WeightsAndDensityAreTheMixtures) {
    const GuideQuadtree tree = learned_from_cone(normalize(Vec3{0.3, 1, 0.2}));
    Material m;
    m.albedo = Rgb{0.7};
    const Vec3 n{0, 1, 0};
    const Bsdf bsdf(m, n);
    const GuidedBsdf guided(bsdf, &tree, 0.5);
    const Vec3 wo = normalize(Vec3{0.4, 1, -0.3});
    Rng rng(11, 0, 0);
    for (int i = 0; i < 2000; ++i) {
        const BsdfSample bs = guided.sample(wo, rng);
        const BsdfValue v = guided.evaluate(wo, bs.wi);
        ASSERT_NEAR(bs.pdf, v.pdf, 1e-12 * v.pdf);
        if (v.pdf > 0) ASSERT_LT(length(bs.weight * bs.pdf - v.f_cos), 1e-12);
    }
    double integral = 0;
    const int samples = 400000;
    for (int i = 0; i < samples; ++i) integral += guided.evaluate(wo, sample_uniform_sphere(rng.uniform(), rng.uniform())).pdf;
    integral *= 4 * kPi / samples;
    EXPECT_NEAR(integral, 0.5 * 1 + 0.5 * 1, 0.02);
}

// A scene of scenes/ at a small size, with integrator.guiding set.
LoadedScene guided_scene(const std::string& file, const char* guiding, int width, int height, uint32_t spp) {
    std::ifstream in(std::string(GLINT_SCENES_DIR) + "/" + file);
    nlohmann::json root = nlohmann::json::parse(in);
    root["integrator"]["guiding"] = guiding;
    LoadedScene s = scene_from_json(root, GLINT_SCENES_DIR);
    s.settings.width = width;
    s.settings.height = height;
    s.settings.spp = spp;
    return s;
}

// Converged, a guided render is the unguided image: the means of the whole image and of each
// quarter agree within their standard errors, on a mesh scene and on smallpt's spheres.
class GuidedRender : public ::testing::TestWithParam<const char*> {};

TEST_P(GuidedRender, ConvergesToTheUnguidedImage) {
    const auto on = testing::render(guided_scene(GetParam(), "on", 32, 24, 512));
    const auto off = testing::render(guided_scene(GetParam(), "off", 32, 24, 512));
    ASSERT_TRUE(on->guide_stats().has_value());
    EXPECT_FALSE(off->guide_stats().has_value());
    for (int q = 0; q < 4; ++q) {
        const int x0 = (q & 1) * 16, y0 = (q >> 1) * 12;
        for (int c = 0; c < 3; ++c) {
            const testing::Estimate a = testing::pooled(on->film(), c, x0, y0, x0 + 16, y0 + 12);
            const testing::Estimate b = testing::pooled(off->film(), c, x0, y0, x0 + 16, y0 + 12);
            EXPECT_LT(std::fabs(a.mean - b.mean), 4.5 * std::hypot(a.sigma, b.sigma))
                << "quarter " << q << " channel " << c << ": " << a.mean << " against " << b.mean;
        }
    }
    EXPECT_TRUE(std::isfinite(on->film().error_estimate()));
}

INSTANTIATE_TEST_SUITE_P(Scenes, GuidedRender, ::testing::Values("cornell_box.json", "cornell.json", "sponza.json"));

// The error estimate of a guided render is within the bounds test_error_estimate.cpp holds the
// unguided one to (measured here: 1.33 with 2 pairs).
TEST(GuidedRenderError, EstimateIsHonest) {
    const testing::Measured m = testing::measure_by_pairs(guided_scene("cornell_box.json", "on", 24, 18, 128), 128, 2);
    EXPECT_GT(m.estimate / m.rmse, 1 / 1.5) << "estimated " << m.estimate << ", measured " << m.rmse;
    EXPECT_LT(m.estimate / m.rmse, 1.5) << "estimated " << m.estimate << ", measured " << m.rmse;
}

// Training reads no thread's order: one thread and two give the same bytes, and so does a job
// split in two parts at sample 64, each part learning the whole job's guide.
TEST(GuidedRenderIdentity, SameBytesForAnyThreadCountAndSplit) {
    const LoadedScene s = guided_scene("cornell_box.json", "on", 24, 18, 128);
    const auto one = testing::render(s, 1), two = testing::render(s, 2);
    EXPECT_EQ(encode_pfm(one->film().mean()), encode_pfm(two->film().mean()));
    LoadedScene first = s, second = s;
    first.settings.spp = second.settings.spp = 64;
    first.settings.adaptive.job_spp = second.settings.adaptive.job_spp = 128;
    second.settings.first_sample = 64;
    const auto a = testing::render(first), b = testing::render(second);
    Film merged = a->film();
    merged.merge(b->film());
    // The same samples, added in another order (two partial sums): equal to rounding.
    for (size_t i = 0; i < merged.pixels().size(); ++i) {
        const PixelSums &whole = two->film().pixels()[i], &parts = merged.pixels()[i];
        ASSERT_EQ(whole.count, parts.count);
        for (int c = 0; c < 3; ++c) ASSERT_NEAR(whole.sum[c], parts.sum[c], 1e-12 * std::fabs(whole.sum[c]) + 1e-300);
    }
}

}  // namespace
}  // namespace glint
