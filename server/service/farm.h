// A farm renders a job's samples on other machines, as parts that each render a range of them
// and a merge that writes the image once every part is done. The service sees a farm through
// this interface alone: it submits a job, polls its parts, cancels them, and follows a
// submission again after a restart. SlurmFarm (service/slurm_farm.h) is the one the server runs;
// the job's side, merging what the parts have rendered, is service/farm_runner.h's.
#pragma once

#include <filesystem>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "assembly/partial_file.h"
#include "render/settings.h"
#include "service/job_spec.h"

namespace glint {

struct FarmError : std::runtime_error {
    using std::runtime_error::runtime_error;
};

// One job's submission: what a restarted server needs to follow it again (the store keeps it as
// JSON, service/job_store.h).
struct FarmRun {
    std::string array, merge;         // the farm's ids of the parts and of the merge
    std::filesystem::path work;       // the parts' folder
    std::vector<std::string> ranges;  // part i's samples, "A:B"
    nlohmann::json to_json() const;
    static FarmRun from_json(const nlohmann::json& j);  // throws FarmError
};

struct PartCounts {
    int queued = 0, running = 0, done = 0, requeued = 0;  // requeued: parts in a second attempt or later
};

// A part as a poll last saw it: its film, and the versions of what was read, so that the next
// poll reads only what changed.
struct PartState {
    std::optional<Partial> film;
    bool done = false;  // the film is the part's final one, not a checkpoint
    int attempt = 0;    // 0 before the part starts; 2 and above once it was requeued
    std::filesystem::file_time_type film_read_at{}, attempt_read_at{};
};

// What one poll found.
struct FarmPoll {
    bool films_changed = false;  // some part's film was read anew
    PartCounts counts;
    std::optional<std::string> failure;  // the message of a part that failed, if one did
};

class Farm {
public:
    virtual ~Farm() = default;

    // Seconds between polls of a job's parts: how soon a part's progress shows.
    virtual double poll_interval() const = 0;
    // Submits job `job_id`: `source` rendered with `settings`, the job's own (so the parts'
    // films carry the job's fingerprint). Throws FarmError with the farm's reason if it refuses.
    virtual FarmRun submit(const std::string& job_id, const SceneSource& source, const RenderSettings& settings) const = 0;
    // A submission from before a restart (FarmRun::to_json's), to follow again; throws FarmError.
    virtual FarmRun resume(const nlohmann::json& saved) const = 0;
    // Looks at the run's parts (`parts` has one entry a range), reading a film or a part's
    // attempt only when it changed since `parts` was filled. Throws PartialError or FileError.
    virtual FarmPoll poll(const FarmRun& run, std::vector<PartState>& parts) const = 0;
    // Cancels the parts and the merge: nothing of the run is left in the farm's queue.
    virtual void cancel(const FarmRun& run) const = 0;
};

// A farm renders every sample a job asks for, each part its own range: InvalidRequest, naming the
// field, for a time limit, a target error or adaptive sampling (whose parts would each adapt on
// their own).
void check_farm_settings(const RenderSettings& settings);

}  // namespace glint
