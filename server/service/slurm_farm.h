// `glint serve --farm slurm`: a job rendered on a Slurm cluster by docker/slurm/submit, as a job
// array of sample ranges and a merge job. The farm submits, counts the parts' states, reads their
// films (a part's checkpoint while it renders, its partial file once done) and cancels; the job
// (service/job.h) merges what the parts have and publishes it as a local job does.
#pragma once

#include <filesystem>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "assembly/partial_file.h"
#include "render/settings.h"
#include "service/service_config.h"

namespace glint {

struct FarmError : std::runtime_error {
    using std::runtime_error::runtime_error;
};

// One job's submission: what a restarted server needs to follow it again.
struct FarmRun {
    std::string array, merge;       // Slurm job ids
    std::filesystem::path work;     // the parts' folder
    std::vector<std::string> ranges;  // part i's samples, "A:B"
    nlohmann::json to_json() const;
    static FarmRun from_json(const nlohmann::json& j);  // throws FarmError
};

struct PartCounts {
    int queued = 0, running = 0, done = 0, requeued = 0;  // requeued: parts in a second attempt or later
};

// A part's film as last read, and the file state it was read at.
struct PartFilm {
    std::optional<Partial> film;
    bool done = false;  // its final partial file, not a checkpoint
    std::filesystem::file_time_type read_at{};
};

class SlurmFarm {
public:
    SlurmFarm(FarmConfig config, std::filesystem::path scenes);

    const FarmConfig& config() const { return config_; }
    // Submits the job of `request` (a scene, or a preset with overrides: http/job_request.h) with
    // the effective `settings`; throws FarmError with sbatch's message if Slurm refuses it.
    FarmRun submit(const std::string& job_id, const std::string& request, const RenderSettings& settings) const;
    PartCounts count(const FarmRun& run) const;
    // Cancels the parts and the merge (nothing is left in Slurm's queue).
    void cancel(const FarmRun& run) const;
    // Reads part i's film again if its file changed since `part` was read: its partial file once
    // done, else its checkpoint. Returns whether `part` changed. Throws PartialError or FileError.
    bool refresh(const FarmRun& run, size_t i, PartFilm& part) const;
    // The message of a part that failed (docker/slurm/render-part's part-i.failed), if any did.
    std::optional<std::string> failure(const FarmRun& run) const;

private:
    // The scene file a part renders and the glint render options that make its settings.
    std::vector<std::string> part_command(const std::filesystem::path& folder, const std::string& request,
                                          const RenderSettings& settings) const;

    FarmConfig config_;
    std::filesystem::path scenes_;
};

}  // namespace glint
