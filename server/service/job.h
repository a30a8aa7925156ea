// One render job as the service sees it: its state, and the snapshot it publishes after every
// pass (the PNG is encoded once per pass, however many clients watch). Watchers wait on it
// without ever blocking the render.
#pragma once

#include <atomic>
#include <chrono>
#include <condition_variable>
#include <memory>
#include <mutex>
#include <string>

#include "assembly/film_exr.h"
#include "denoise/half_buffers.h"
#include "assembly/partial_file.h"
#include "assembly/scene_loader.h"
#include "render/renderer.h"
#include "service/denoise_gate.h"
#include "service/job_state.h"
#include "service/job_store.h"
#include "service/slurm_farm.h"

namespace glint {

struct JobSnapshot {
    uint64_t frame = 0;  // 0 until the first pass; then one more per pass (and one at the end)
    JobState state = JobState::queued;
    Progress progress;
    std::shared_ptr<const std::vector<uint8_t>> png;  // null until the first pass
    std::shared_ptr<const Image> image;               // the linear mean image of that frame
    // The film's other EXR layers at that frame (io/exr_file.h: sample counts, variance, AOVs);
    // null for a preview, which has none.
    std::shared_ptr<const std::vector<ExrLayer>> layers;
    // An adaptive job's camera samples per pixel at that frame, as grey (black 0, white
    // samples_max, linear); null for other jobs, whose pixels all have spp_done.
    std::shared_ptr<const std::vector<uint8_t>> samples_png;
    uint64_t samples_max = 0;
    // What the denoiser reads of that frame's film (null for the first preview): 52 bytes a
    // pixel, so that a denoised preview can be made on request while the film goes on changing.
    std::shared_ptr<const HalfBuffers> halves;
    std::string error;                                // why a failed job failed
    std::optional<PartCounts> parts;                  // a farm job's parts, once submitted
    std::optional<StopReason> stop;                   // why it ended (not set for a failed job)
    bool preview = false;                             // the frame is the throwaway first preview
};

// A job rendered on a farm rather than on the server's threads: the farm, the request its parts
// are made from, and its submission when a restarted server takes the job back.
struct FarmJob {
    const SlurmFarm* farm = nullptr;
    std::string request;
    std::optional<FarmRun> run;
};

class Job {
public:
    // With a store, the job saves its state when it changes and its film after passes (at most
    // every checkpoint interval) and at the end; see job_store.h.
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
    bool on_farm() const { return farm_.farm != nullptr; }
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

    JobSnapshot snapshot() const;
    // The latest frame denoised (denoise/denoiser.h), as PNG; made on the first request for a
    // frame, inside `gate`, and kept until the next. Null until a pass has finished. Throws Busy
    // (service/errors.h) when the frame is not made yet and the gate is full or this job's
    // frame is being made for another request: a request never waits for a preview.
    std::shared_ptr<const std::vector<uint8_t>> denoised_png(DenoiseGate& gate) const;
    // Waits until there is a frame newer than `after`, the job is final, or `timeout` passes.
    JobSnapshot wait(uint64_t after, std::chrono::milliseconds timeout) const;

private:
    void render_here(ThreadPool& pool);
    // The farm's side of run(): submits the parts (or follows a restored submission), publishes
    // what they have rendered as it arrives, and ends when every part is done, one fails, or
    // the job is cancelled (which cancels the parts) or suspended (which leaves them running).
    void render_on_farm();
    // Merges the parts' films into the job's film; returns whether every part is done (their
    // films are then moved out: the job's film is final).
    bool merge_parts(std::vector<PartFilm>& parts);
    void end_failed(const std::string& error, const Progress& progress);
    void publish(JobState state, const Progress& progress);
    // Publishes `image` as a frame without touching the film (the first preview).
    void publish_preview(const Image& image);
    // The frame's film data (null for a preview), copied at each pass so that the routes
    // serve a consistent frame while the film goes on changing: the denoiser's inputs and the
    // EXR's other layers.
    void publish_frame(Image frame, std::vector<ExrLayer> layers, std::shared_ptr<const HalfBuffers> halves,
                       JobState state, const Progress& progress, bool preview);
    void set_stop(StopReason reason);
    // The job's state.json as it would be in `state`; record_locked() with mutex_ held.
    JobRecord record(JobState state, const std::string& error, const Progress& progress) const;
    JobRecord record_locked(JobState state, const std::string& error, const Progress& progress) const;
    Progress with_earlier_time(Progress p) const;
    // Store writes: a failure is logged, never stops the render or a request.
    void save_state(JobState state, const std::string& error, const Progress& progress) const;
    void write_state(const JobRecord& record) const;
    void checkpoint(const Progress& progress);
    void save_final(JobState state, const Progress& progress) const;

    const std::string id_;
    RenderJob render_;
    std::chrono::system_clock::time_point created_;
    const std::vector<std::string> warnings_;
    const JobStore* store_;
    uint64_t fingerprint_ = 0;  // of scene and settings, written into the film files
    double seconds_before_ = 0;  // rendering time before a restart
    std::chrono::steady_clock::time_point last_checkpoint_ = std::chrono::steady_clock::now();
    std::atomic<bool> suspended_{false};
    std::atomic<bool> cancelled_{false};
    std::atomic<int> priority_;
    FarmJob farm_;
    mutable std::mutex mutex_;
    mutable std::condition_variable changed_;
    JobSnapshot snapshot_;
    mutable std::mutex denoised_mutex_;  // guards the three below, never held while denoising
    mutable bool denoising_ = false;     // a request is making this job's denoised frame
    mutable uint64_t denoised_frame_ = 0;
    mutable std::shared_ptr<const std::vector<uint8_t>> denoised_png_;
};

}  // namespace glint
