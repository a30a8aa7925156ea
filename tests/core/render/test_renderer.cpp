// Progressive rendering: bit-identical images whatever the thread count or pass split, and
// each way a job can stop.
#include <gtest/gtest.h>

#include "io/image_io.h"
#include "support/test_support.h"

namespace glint {
namespace {

TEST(Renderer, ImagesAreBitIdenticalWithOneOrTwoThreads) {
    const LoadedScene s = testing::small_cornell(32);
    const auto one = testing::render(s, 1), two = testing::render(s, 2);
    EXPECT_EQ(encode_pfm(one->film().mean()), encode_pfm(two->film().mean()));
    EXPECT_EQ(encode_png(one->film().mean(), Encoding::gamma22), encode_png(two->film().mean(), Encoding::gamma22));
    EXPECT_EQ(one->film().error_estimate(), two->film().error_estimate());
}

TEST(Renderer, PassSplitDoesNotChangeTheImage) {
    const LoadedScene s = testing::small_cornell(16);
    ThreadPool pool(2);
    RenderJob whole(s.scene, s.settings), split(s.scene, s.settings);
    whole.render_pass(pool, 0, 16);
    split.render_pass(pool, 0, 4);
    split.render_pass(pool, 4, 12);
    split.render_pass(pool, 12, 16);
    EXPECT_EQ(encode_pfm(whole.film().mean()), encode_pfm(split.film().mean()));
}

TEST(Renderer, DifferentSeedsGiveDifferentImages) {
    LoadedScene s = testing::small_cornell(8);
    const auto a = testing::render(s);
    s.settings.seed = 1;
    const auto b = testing::render(s);
    EXPECT_NE(encode_pfm(a->film().mean()), encode_pfm(b->film().mean()));
}

TEST(Renderer, CancelStopsAfterThePassAndKeepsItsSamples) {
    const LoadedScene s = testing::small_cornell(4096);
    ThreadPool pool(2);
    RenderJob job(s.scene, s.settings);
    int passes = 0;
    const StopReason reason = job.run(pool, [&](const Progress&) {
        if (++passes == 2) job.cancel();
    });
    EXPECT_EQ(reason, StopReason::cancelled);
    EXPECT_EQ(passes, 2);
    EXPECT_GE(job.film().pixel(0, 0).count, job.progress().spp_done);
    EXPECT_GT(job.progress().spp_done, 0u);
}

// An endless job (2^20 spp) that only `settings` can stop; returns why it stopped.
StopReason run_unbounded(const std::function<void(RenderSettings&)>& settings, std::unique_ptr<RenderJob>& job) {
    LoadedScene s = testing::small_cornell(1u << 20);
    settings(s.settings);
    ThreadPool pool(2);
    job = std::make_unique<RenderJob>(s.scene, s.settings);
    return job->run(pool);
}

TEST(Renderer, StopsAtTheTimeLimit) {
    std::unique_ptr<RenderJob> job;
    EXPECT_EQ(run_unbounded([](RenderSettings& s) { s.time_limit = 0.3; }, job), StopReason::time_limit);
    EXPECT_LT(job->progress().spp_done, 1u << 20);
}

TEST(Renderer, StopsAtTheTargetError) {
    std::unique_ptr<RenderJob> job;
    EXPECT_EQ(run_unbounded([](RenderSettings& s) { s.target_error = 0.2; }, job), StopReason::target_error);
    EXPECT_LE(job->film().error_estimate(), 0.2);
}

// The error estimate rests on it: a round of the tent filter is its four subpixels, one sample
// each, and the film must see them as one, in the half of the sampler's replicate they drew from
// (the even rounds: 0 and 2 of the tent's 3, 6 of the box's 12).
TEST(Renderer, AddsSamplesToTheFilmInWholeRoundsOfTheirHalf) {
    LoadedScene s = testing::small_cornell(12);
    s.settings.width = s.settings.height = 4;
    for (const auto& [filter, first_half] : {std::pair{Filter::tent, 8u}, std::pair{Filter::box, 6u}}) {
        s.settings.filter = filter;
        const auto job = testing::render(s);
        for (const PixelSums& px : job->film().pixels()) {
            EXPECT_EQ(px.count, 12u);
            EXPECT_EQ(px.half_count, first_half);
        }
    }
}

TEST(Renderer, TentFilterRoundsSampleCountsUpToWholeSubpixelRounds) {
    LoadedScene s = testing::small_cornell(5);
    EXPECT_EQ(RenderJob(s.scene, s.settings).settings().spp, 8u);
    s.settings.filter = Filter::box;
    EXPECT_EQ(RenderJob(s.scene, s.settings).settings().spp, 5u);
}

}  // namespace
}  // namespace glint
