// One render job as the service sees it: its scene and settings, its status (service/
// job_status.h) and the parts that do its work, each in the file named after it: the runner that
// renders it here or on a farm (job_runner.h), the publisher of its frames (frame_publisher.h),
// its writes to the store (job_saver.h) and its denoised preview (denoised_preview.h). The job
// manager decides when it runs; the job only runs.
#pragma once

#include <atomic>
#include <chrono>
#include <memory>
#include <string>
#include <vector>

#include "assembly/scene_loader.h"
#include "render/renderer.h"
#include "service/denoise_gate.h"
#include "service/denoised_preview.h"
#include "service/farm_runner.h"
#include "service/frame_publisher.h"
#include "service/job_control.h"
#include "service/job_runner.h"
#include "service/job_saver.h"
#include "service/job_status.h"
#include "service/job_store.h"

namespace glint {

class Job {
public:
    // With a store, the job saves its state when it changes and its film after passes (at most
    // every checkpoint interval) and at the end; see job_store.h. With `farm.farm`, it renders
    // there rather than on the server's threads.
    Job(std::string id, const LoadedScene& scene, const JobStore* store = nullptr,
        std::chrono::system_clock::time_point created = std::chrono::system_clock::now(), FarmJob farm = {},
        int priority = 0);

    const std::string& id() const { return id_; }
    const RenderSettings& settings() const { return render_.settings(); }
    std::chrono::system_clock::time_point created() const { return created_; }
    // The scene's warnings (what it asks for that glint does not model), fixed at submission.
    const std::vector<std::string>& warnings() const { return warnings_; }
    int priority() const { return priority_; }
    // Changes a queued or running job's priority (service/priority.h), and with it the share of
    // the render threads it gets from its next tile on; false (and nothing changed) once the
    // job has ended. The job manager reads priorities when it picks the next job to start.
    bool set_priority(int priority);

    // Renders to the end on `pool`, or on the farm (called by the job manager's slot thread).
    void run(ThreadPool& pool);
    bool on_farm() const { return runner_->on_farm(); }
    // Queued: ends at once. Running: the pass in flight stops after its tiles in progress.
    void cancel();
    // A graceful stop with a store: the job ends at its next pass boundary with a checkpoint and
    // stays queued in the store, to resume when the server starts again (in memory it ends).
    void suspend();

    // A restarted server's jobs. Before run(): continue from a checkpoint's film (whole passes);
    // `saved` is the progress the store last recorded. Throws std::invalid_argument if it does not fit.
    void resume(const Partial& checkpoint, const Progress& saved);
    // A job that had ended: its state and, if it rendered anything, the film it ended with.
    // Throws std::invalid_argument if the film is not this job's.
    void restore_final(const JobRecord& record, const Partial* film);
    // Ends the job as failed with `error` (shown with its status), without an image.
    void fail(const std::string& error);

    JobSnapshot snapshot() const { return status_.snapshot(); }
    // The latest frame denoised, as PNG (service/denoised_preview.h); null until a pass has
    // finished; throws Busy rather than wait.
    std::shared_ptr<const std::vector<uint8_t>> denoised_png(DenoiseGate& gate) const;
    // Waits until there is a frame newer than `after`, the job is final, or `timeout` passes.
    JobSnapshot wait(uint64_t after, std::chrono::milliseconds timeout) const { return status_.wait(after, timeout); }

private:
    const std::string id_;
    RenderJob render_;
    std::chrono::system_clock::time_point created_;
    const std::vector<std::string> warnings_;
    uint64_t fingerprint_;  // of scene and settings, written into the film files; 0 if none is
    double seconds_before_ = 0;  // rendering time before a restart
    std::atomic<int> priority_;
    JobStatus status_;
    FramePublisher publisher_;
    JobSaver saver_;
    JobControl control_;
    std::unique_ptr<JobRunner> runner_;
    mutable DenoisedPreview denoised_;
};

}  // namespace glint
