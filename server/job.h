// One render job as the service sees it: its state, and the snapshot it publishes after every
// pass (the PNG is encoded once per pass, however many clients watch). Watchers wait on it
// without ever blocking the render.
#pragma once

#include <chrono>
#include <condition_variable>
#include <memory>
#include <mutex>
#include <string>

#include <nlohmann/json.hpp>

#include "renderer.h"
#include "scene_loader.h"

namespace glint {

enum class JobState { queued, running, done, cancelled, failed };
const char* to_string(JobState state);
inline bool is_final(JobState s) { return s == JobState::done || s == JobState::cancelled || s == JobState::failed; }

struct JobSnapshot {
    uint64_t frame = 0;  // 0 until the first pass; then one more per pass (and one at the end)
    JobState state = JobState::queued;
    Progress progress;
    std::shared_ptr<const std::vector<uint8_t>> png;  // null until the first pass
    std::shared_ptr<const Image> image;               // the linear mean image of that frame
};

class Job {
public:
    Job(std::string id, const LoadedScene& scene);

    const std::string& id() const { return id_; }
    const RenderSettings& settings() const { return render_.settings(); }

    // Renders to the end on `pool` (called by the job manager's slot thread).
    void run(ThreadPool& pool);
    // Queued: ends at once. Running: the pass in flight stops after its tiles in progress.
    void cancel();

    JobSnapshot snapshot() const;
    // Waits until there is a frame newer than `after`, the job is final, or `timeout` passes.
    JobSnapshot wait(uint64_t after, std::chrono::milliseconds timeout) const;
    nlohmann::json status() const;

private:
    void publish(JobState state, const Progress& progress);

    const std::string id_;
    RenderJob render_;
    std::chrono::system_clock::time_point created_;
    mutable std::mutex mutex_;
    mutable std::condition_variable changed_;
    JobSnapshot snapshot_;
};

}  // namespace glint
