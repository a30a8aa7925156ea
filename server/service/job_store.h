// `glint serve --store DIR`: every job's request, state and film on disk, so a server that is
// killed and restarted on the same folder lists the same jobs, resumes the unfinished ones from
// their last checkpoint and serves the finished ones again.
//
// One folder per job, DIR/{id}/:
//   request.json        the request body as received (a scene, or a preset with overrides)
//   state.json          {"created", "state", "error", "progress", "priority", "stop_reason"}:
//                       what GET /jobs/{id} shows (progress as service/progress_json.h writes
//                       it; the last two absent in a store from before they were kept)
//   checkpoint.glntpart the film after a whole pass (samples [first, end) of every pixel), in
//                       the partial-file format of core/assembly/partial_file.h (fingerprint, checksum)
//   final.glntpart      the film as the job ended (a cancelled job's last pass may be partial)
//   farm.json           a job rendered on a farm: its Slurm submission (service/slurm_farm.h)
// Every file is written atomically (core/base/files.h): a crash leaves the old file or the new one.
#pragma once

#include <chrono>
#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "assembly/partial_file.h"
#include "render/renderer.h"
#include "service/job_state.h"
#include "service/service_config.h"

namespace glint {

// A job's state.json.
struct JobRecord {
    std::chrono::system_clock::time_point created;
    JobState state = JobState::queued;
    std::string error;
    Progress progress;
    int priority = 0;                 // as changed since the request, which gave the first
    std::optional<StopReason> stop;  // why it ended, once it has
};

// What the store holds about one job.
struct StoredJob {
    std::string id;
    std::string request;
    JobRecord record;
    std::string farm;  // farm.json's text, for a job submitted to a farm; else empty
};

enum class FilmFile { checkpoint, final };

class JobStore {
public:
    explicit JobStore(StoreConfig config);  // creates the folder; throws FileError

    const StoreConfig& config() const { return config_; }

    // Every job in the folder, oldest first. A job whose request or state cannot be read is
    // logged and left out (and left on disk for a person to look at).
    std::vector<StoredJob> load() const;
    void save_request(const std::string& id, const std::string& request) const;
    void save_state(const std::string& id, const JobRecord& record) const;
    void save_film(const std::string& id, FilmFile which, const Partial& film) const;
    void save_farm(const std::string& id, const std::string& farm) const;
    // Throws PartialError (corrupt, truncated) or FileError.
    Partial load_film(const std::string& id, FilmFile which) const;
    bool has_film(const std::string& id, FilmFile which) const;
    void remove(const std::string& id) const;

    std::filesystem::path film_path(const std::string& id, FilmFile which) const;
    uint64_t job_bytes(const std::string& id) const;
    uint64_t bytes_used() const;

private:
    std::filesystem::path folder(const std::string& id) const { return config_.dir / id; }

    StoreConfig config_;
};

}  // namespace glint
