// A job's status moves only as a job's life allows, counts its frames, and keeps what a frame
// without a samples picture does not replace.
#include <gtest/gtest.h>

#include "service/job_status.h"

namespace glint {
namespace {

JobFrame frame_with_png(uint8_t byte) {
    JobFrame frame;
    frame.png = std::make_shared<const std::vector<uint8_t>>(1, byte);
    return frame;
}

TEST(JobState, MovesAsAJobsLifeAllows) {
    constexpr JobState all[] = {JobState::queued, JobState::running, JobState::done, JobState::cancelled,
                                JobState::failed};
    for (JobState from : all)
        for (JobState to : all) {
            const bool expected = from == JobState::queued || (from == JobState::running && to != JobState::queued);
            EXPECT_EQ(can_move(from, to), expected) << to_string(from) << " to " << to_string(to);
        }
}

TEST(JobStatus, StartsOnceAndOnlyFromQueued) {
    JobStatus status(Progress{});
    EXPECT_TRUE(status.start());
    EXPECT_EQ(status.snapshot().state, JobState::running);
    EXPECT_FALSE(status.start());
    EXPECT_EQ(status.snapshot().frame, 0u);  // starting is not a frame
}

TEST(JobStatus, EveryPublishIsANewFrameUntilTheJobEnds) {
    JobStatus status(Progress{});
    ASSERT_TRUE(status.start());
    Progress p;
    p.spp_done = 4;
    EXPECT_TRUE(status.publish(frame_with_png(1), JobState::running, p));
    EXPECT_TRUE(status.publish(frame_with_png(2), JobState::done, p));
    EXPECT_FALSE(status.publish(frame_with_png(3), JobState::running, p));
    EXPECT_FALSE(status.publish(frame_with_png(3), JobState::failed, p));
    const JobSnapshot s = status.snapshot();
    EXPECT_EQ(s.frame, 2u);
    EXPECT_EQ(s.state, JobState::done);
    EXPECT_EQ(s.progress.spp_done, 4u);
    EXPECT_EQ((*s.png)[0], 2);
}

TEST(JobStatus, ASamplesPictureStaysUntilAFrameBringsANewOne) {
    JobStatus status(Progress{});
    ASSERT_TRUE(status.start());
    JobFrame with_samples = frame_with_png(1);
    with_samples.samples_png = std::make_shared<const std::vector<uint8_t>>(1, 9);
    with_samples.samples_max = 7;
    status.publish(with_samples, JobState::running, {});
    JobFrame preview = frame_with_png(2);
    preview.preview = true;
    status.publish(preview, JobState::running, {});
    const JobSnapshot s = status.snapshot();
    EXPECT_TRUE(s.preview);
    ASSERT_TRUE(s.samples_png);
    EXPECT_EQ((*s.samples_png)[0], 9);
    EXPECT_EQ(s.samples_max, 7u);
}

TEST(JobStatus, OnlyAQueuedJobEndsWithoutRunningWhenAskedSo) {
    JobStatus running(Progress{});
    ASSERT_TRUE(running.start());
    EXPECT_FALSE(running.end_without_frame(JobState::cancelled, "", StopReason::cancelled, true));
    EXPECT_EQ(running.snapshot().state, JobState::running);

    JobStatus queued(Progress{});
    JobSnapshot seen_first;
    EXPECT_TRUE(queued.end_without_frame(JobState::cancelled, "", StopReason::cancelled, true,
                                         [&](const JobSnapshot& next) { seen_first = next; }));
    const JobSnapshot s = queued.snapshot();
    EXPECT_EQ(seen_first.state, JobState::cancelled);  // `before` sees the snapshot it is about to become
    EXPECT_EQ(seen_first.frame, s.frame);
    EXPECT_EQ(s.frame, 1u);
    EXPECT_EQ(s.stop, StopReason::cancelled);
    EXPECT_FALSE(queued.start());
    EXPECT_FALSE(queued.end_without_frame(JobState::failed, "late", std::nullopt, false));
    EXPECT_EQ(queued.snapshot().error, "");
}

TEST(JobStatus, AFailureDropsThePictures) {
    JobStatus status(Progress{});
    ASSERT_TRUE(status.start());
    status.publish(frame_with_png(1), JobState::running, {});
    EXPECT_TRUE(status.end_without_frame(JobState::failed, "broken", std::nullopt, false));
    const JobSnapshot s = status.snapshot();
    EXPECT_EQ(s.state, JobState::failed);
    EXPECT_EQ(s.error, "broken");
    EXPECT_FALSE(s.png);
    EXPECT_EQ(s.frame, 2u);
}

}  // namespace
}  // namespace glint
