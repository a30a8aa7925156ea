// `glint serve --farm slurm`: jobs rendered on a Slurm cluster by docker/slurm/submit, as a job
// array of sample ranges and a merge job. Each part leaves its state in files of the run's
// folder, which a poll stats and reads only when they changed: part-i.attempt (the attempt that
// runs), part-i.checkpoint while it renders, part-i.partial once done, part-i.failed if it failed.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "service/farm.h"
#include "service/service_config.h"

namespace glint {

class SlurmFarm : public Farm {
public:
    // `scenes` is the scenes folder: presets are read from it and meshes looked up in it.
    SlurmFarm(FarmConfig config, std::filesystem::path scenes);

    double poll_interval() const override { return config_.poll_interval; }
    // Throws FarmError with sbatch's message if Slurm refuses the job.
    FarmRun submit(const std::string& job_id, const SceneSource& source, const RenderSettings& settings) const override;
    FarmRun resume(const nlohmann::json& saved) const override;
    FarmPoll poll(const FarmRun& run, std::vector<PartState>& parts) const override;
    void cancel(const FarmRun& run) const override;

private:
    // The scene file a part renders and the glint render options that make the job's settings.
    std::vector<std::string> part_command(const std::filesystem::path& folder, const SceneSource& source,
                                          const RenderSettings& settings) const;
    // Squeue's count of the parts waiting and running, added to `counts`.
    void count_queue(const FarmRun& run, PartCounts& counts) const;

    FarmConfig config_;
    std::filesystem::path scenes_;
};

}  // namespace glint
