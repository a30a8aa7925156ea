// A farm job's logic over a farm that is a test double: the parts' films merge to the local
// render's bytes; a failed part, a cancel or a suspend each end the job as they should; a
// submission a restarted server took back is followed, not made again; a foreign film fails it.
#include <gtest/gtest.h>

#include <atomic>
#include <mutex>
#include <thread>

#include "assembly/fingerprint.h"
#include "io/image_io.h"
#include "service/errors.h"
#include "service/job.h"
#include "service/job_manager.h"
#include "support/test_support.h"

namespace glint {
namespace {

const std::vector<std::string> kRanges = {"0:8", "8:12", "12:16"};

// Samples [first, end) of `s` as a part renders them, with `print` as the part's fingerprint.
Partial render_part(LoadedScene s, uint32_t first, uint32_t end, uint64_t print) {
    s.settings.first_sample = first;
    s.settings.spp = end - first;
    return partial_of(*testing::render(s), print, end - first);
}

// Hands out part i's final film on the (i+1)-th poll, unless told to hold them back or fail.
class FakeFarm : public Farm {
public:
    explicit FakeFarm(std::vector<Partial> films) : films_(std::move(films)) {}

    double poll_interval() const override { return 0.001; }
    FarmRun submit(const std::string& job_id, const SceneSource& source, const RenderSettings&) const override {
        std::lock_guard lock(mutex_);
        ++submits;
        submitted_preset = source.preset;
        return {"array-" + job_id, "merge-" + job_id, "/nowhere", kRanges};
    }
    FarmRun resume(const nlohmann::json& saved) const override { return FarmRun::from_json(saved); }
    FarmPoll poll(const FarmRun& run, std::vector<PartState>& parts) const override {
        std::lock_guard lock(mutex_);
        EXPECT_EQ(parts.size(), run.ranges.size());
        FarmPoll found;
        if (failure) found.failure = failure;
        const size_t ready = hold ? 0 : std::min<size_t>(++polls_released, parts.size());
        for (size_t i = 0; i < ready; ++i) {
            if (!parts[i].done) {
                parts[i].film = films_[i];
                parts[i].done = found.films_changed = true;
            }
            ++found.counts.done;
        }
        ++polls;
        return found;
    }
    void cancel(const FarmRun&) const override { ++cancels; }

    mutable std::atomic<int> submits{0}, cancels{0}, polls{0};
    mutable std::string submitted_preset;
    std::atomic<bool> hold{false};
    std::optional<std::string> failure;

private:
    std::vector<Partial> films_;
    mutable size_t polls_released = 0;
    mutable std::mutex mutex_;
};

struct FarmJobTest : ::testing::Test {
    LoadedScene scene = testing::small_cornell(16);
    uint64_t print = fingerprint(*scene.scene, scene.settings);
    FakeFarm farm{{render_part(scene, 0, 8, print), render_part(scene, 8, 12, print), render_part(scene, 12, 16, print)}};
    ThreadPool pool{1};

    std::unique_ptr<Job> job(std::optional<FarmRun> run = std::nullopt) {
        return std::make_unique<Job>("0123456789abcdef", scene, nullptr, std::chrono::system_clock::now(),
                                     FarmJob{&farm, {"cornell", {}}, std::move(run)});
    }
    // Runs `j` on a thread until `when` holds, does `act`, and waits for the job to end.
    template <class When, class Act>
    JobSnapshot run_and(Job& j, When when, Act act) {
        std::thread runner([&] { j.run(pool); });
        while (!when()) std::this_thread::sleep_for(std::chrono::milliseconds(1));
        act();
        runner.join();
        return j.snapshot();
    }
};

TEST_F(FarmJobTest, MergedPartsAreTheLocalRendersBytes) {
    auto j = job();
    ASSERT_TRUE(j->on_farm());
    j->run(pool);
    const JobSnapshot s = j->snapshot();
    EXPECT_EQ(s.state, JobState::done);
    EXPECT_EQ(s.stop, StopReason::completed);
    EXPECT_EQ(s.progress.spp_done, 16u);
    ASSERT_TRUE(s.parts);
    EXPECT_EQ(s.parts->done, 3);
    EXPECT_EQ(farm.submits, 1);
    EXPECT_EQ(farm.submitted_preset, "cornell");
    EXPECT_EQ(farm.cancels, 0);
    // Three polls each bring one more part: two previews of the parts so far, then the end.
    EXPECT_EQ(s.frame, 3u);
    const auto whole = testing::render(scene);
    EXPECT_EQ(encode_pfm(*s.image), encode_pfm(whole->film().mean()));
    EXPECT_EQ(*s.png, encode_png(whole->film().mean(), scene.settings.encoding));
}

TEST_F(FarmJobTest, AFailedPartFailsTheJobAndCancelsTheRest) {
    farm.failure = "part 1 (samples 8:12, on node2) failed with exit code 1";
    auto j = job();
    j->run(pool);
    const JobSnapshot s = j->snapshot();
    EXPECT_EQ(s.state, JobState::failed);
    EXPECT_EQ(s.error, *farm.failure);
    EXPECT_EQ(farm.cancels, 1);
}

TEST_F(FarmJobTest, ACancelCancelsThePartsAndKeepsWhatTheyRendered) {
    farm.hold = true;
    auto j = job();
    const JobSnapshot s = run_and(*j, [&] { return farm.polls > 0; }, [&] { j->cancel(); });
    EXPECT_EQ(s.state, JobState::cancelled);
    EXPECT_EQ(s.stop, StopReason::cancelled);
    EXPECT_EQ(farm.cancels, 1);
}

TEST_F(FarmJobTest, ASuspendLeavesThePartsRunning) {
    farm.hold = true;
    auto j = job();
    const JobSnapshot s = run_and(*j, [&] { return farm.polls > 0; }, [&] { j->suspend(); });
    EXPECT_EQ(s.state, JobState::cancelled);  // in memory; a store would keep it queued
    EXPECT_FALSE(s.stop);
    EXPECT_EQ(farm.cancels, 0);
}

TEST_F(FarmJobTest, ARestoredSubmissionIsFollowedNotMadeAgain) {
    auto j = job(FarmRun{"41", "42", "/nowhere", kRanges});
    j->run(pool);
    EXPECT_EQ(j->snapshot().state, JobState::done);
    EXPECT_EQ(farm.submits, 0);
}

TEST_F(FarmJobTest, ARestoredSubmissionCancelledWhileQueuedIsCancelledOnTheFarm) {
    auto j = job(FarmRun{"41", "42", "/nowhere", kRanges});
    j->cancel();
    EXPECT_EQ(j->snapshot().state, JobState::cancelled);
    EXPECT_EQ(farm.cancels, 1);
    j->run(pool);
    EXPECT_EQ(farm.polls, 0);
}

TEST_F(FarmJobTest, APartOfAnotherSceneFailsTheJob) {
    FakeFarm foreign{{render_part(scene, 0, 8, print + 1), render_part(scene, 8, 12, print),
                      render_part(scene, 12, 16, print)}};
    Job j("0123456789abcdef", scene, nullptr, std::chrono::system_clock::now(), FarmJob{&foreign, {}, std::nullopt});
    j.run(pool);
    const JobSnapshot s = j.snapshot();
    EXPECT_EQ(s.state, JobState::failed);
    EXPECT_NE(s.error.find("fingerprint differs"), std::string::npos) << s.error;
    EXPECT_EQ(foreign.cancels, 1);
}

TEST(FarmJobManager, AFarmTakesNoTimeLimitTargetErrorOrAdaptiveSampling) {
    ThreadPool pool(1);
    JobManager jobs(pool, ServiceConfig{}, std::make_unique<FakeFarm>(std::vector<Partial>{}));
    const auto refused_at = [&](auto change) {
        JobSpec spec{testing::small_cornell(16), 0, {}};
        change(spec.scene.settings);
        try {
            jobs.submit(spec);
        } catch (const InvalidRequest& e) {
            return e.path();
        }
        return std::string("accepted");
    };
    EXPECT_EQ(refused_at([](RenderSettings& s) { s.time_limit = 1; }), "film.time_limit");
    EXPECT_EQ(refused_at([](RenderSettings& s) { s.target_error = 0.1; }), "film.target_error");
    EXPECT_EQ(refused_at([](RenderSettings& s) { s.adaptive.threshold = 0.01; }), "film.adaptive");
    EXPECT_EQ(jobs.queued() + jobs.running(), 0u);
}

}  // namespace
}  // namespace glint
