// A job rendered on a farm (service/farm.h): it submits the parts, or follows a submission a
// restarted server took back; merges what they have rendered as it arrives and publishes it; and
// ends when every part is done, when one fails, or when the job is cancelled (which cancels the
// parts) or suspended (which leaves them running for the restarted server to follow).
#pragma once

#include <optional>
#include <vector>

#include "service/farm.h"
#include "service/job_runner.h"

namespace glint {

// A farm job before it runs: the farm, what its parts render, and its submission if a restarted
// server took it back.
struct FarmJob {
    const Farm* farm = nullptr;
    SceneSource source;
    std::optional<FarmRun> run;
};

class FarmRunner : public JobRunner {
public:
    // `fingerprint` is the job's: every part's film must carry it.
    FarmRunner(JobContext job, FarmJob farm, uint64_t fingerprint)
        : job_(job), farm_(std::move(farm)), fingerprint_(fingerprint) {}

    void run(ThreadPool& pool) override;
    void cancel_before_start() override;
    bool on_farm() const override { return true; }

private:
    Progress progress() const;  // the merged film's, with the time since the run started
    void submit();
    // Polls the parts once and publishes what changed; returns whether every part is done.
    bool poll(std::vector<PartState>& parts);
    // Merges the parts' films into the job's film; returns whether every part is done (their
    // films are then moved out: the job's film is final).
    bool merge_parts(std::vector<PartState>& parts);
    // Follows the run until it ends; returns false if the job was suspended meanwhile.
    bool follow();

    JobContext job_;
    FarmJob farm_;
    uint64_t fingerprint_;
    std::chrono::steady_clock::time_point start_;
};

}  // namespace glint
