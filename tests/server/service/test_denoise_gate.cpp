// The bound on denoised previews made at once: a request beyond it is refused as busy at once,
// a frame already made is served whatever the gate holds, and a place is given back.
#include <gtest/gtest.h>

#include "service/errors.h"
#include "service/job_manager.h"
#include "support/test_support.h"

namespace glint {
namespace {

using namespace std::chrono_literals;

std::shared_ptr<Job> finished_job(JobManager& jobs) {
    auto job = jobs.submit({testing::small_cornell(16), 0, {}});
    for (JobSnapshot s = job->snapshot(); !is_final(s.state); s = job->wait(s.frame, 1s)) {}
    return job;
}

TEST(DenoiseGate, APreviewBeyondTheLimitIsRefusedAsBusyAndAMadeOneIsServed) {
    ThreadPool pool(1);
    ServiceConfig config;
    config.max_denoising = 1;
    JobManager jobs(pool, config);
    const auto job = finished_job(jobs);
    DenoiseGate& gate = jobs.denoise_gate();
    ASSERT_TRUE(gate.try_enter());  // another request is making a preview
    EXPECT_THROW(job->denoised_png(gate), Busy);
    gate.leave();
    const auto png = job->denoised_png(gate);
    ASSERT_TRUE(png);
    EXPECT_FALSE(png->empty());
    ASSERT_TRUE(gate.try_enter());  // the place came back; with it held, the made frame is served
    EXPECT_EQ(job->denoised_png(gate), png);
    EXPECT_FALSE(gate.try_enter());
    gate.leave();
}

}  // namespace
}  // namespace glint
