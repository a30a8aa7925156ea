// A job's status as every watcher sees it: its state, the latest frame it published (the PNG
// encoded once per frame, however many clients watch) and why it ended. Watchers wait on it
// without ever blocking the render. Every change goes through a move that job_state.h allows:
// a job that has ended stays as it ended.
#pragma once

#include <chrono>
#include <condition_variable>
#include <cstdint>
#include <functional>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <vector>

#include "base/image.h"
#include "denoise/half_buffers.h"
#include "io/exr_file.h"
#include "render/renderer.h"
#include "service/farm.h"
#include "service/job_state.h"

namespace glint {

// One frame's pictures (service/frame_publisher.h makes them).
struct JobFrame {
    std::shared_ptr<const std::vector<uint8_t>> png;  // null: the job has no picture yet
    std::shared_ptr<const Image> image;               // the linear mean image
    // The film's other EXR layers (io/exr_file.h: sample counts, variance, AOVs); null for a
    // preview or a restored film, which have none.
    std::shared_ptr<const std::vector<ExrLayer>> layers;
    // What the denoiser reads of the film (null for the first preview): 52 bytes a pixel, so that
    // a denoised preview can be made on request while the film goes on changing.
    std::shared_ptr<const HalfBuffers> halves;
    // An adaptive job's camera samples per pixel, as grey (black 0, white samples_max, linear);
    // null for other jobs, whose pixels all have spp_done, and for previews.
    std::shared_ptr<const std::vector<uint8_t>> samples_png;
    uint64_t samples_max = 0;
    bool preview = false;  // the throwaway first preview
};

struct JobSnapshot {
    uint64_t frame = 0;  // 0 until the first pass; then one more per pass (and one at the end)
    JobState state = JobState::queued;
    Progress progress;
    std::shared_ptr<const std::vector<uint8_t>> png;
    std::shared_ptr<const Image> image;
    std::shared_ptr<const std::vector<ExrLayer>> layers;
    std::shared_ptr<const std::vector<uint8_t>> samples_png;  // the latest an adaptive job published
    uint64_t samples_max = 0;
    std::shared_ptr<const HalfBuffers> halves;
    std::string error;                 // why a failed job failed
    std::optional<PartCounts> parts;   // a farm job's parts, once submitted
    std::optional<StopReason> stop;    // why it ended (not set for a failed job)
    bool preview = false;              // the frame is the throwaway first preview
};

class JobStatus {
public:
    explicit JobStatus(const Progress& progress);

    JobSnapshot snapshot() const;
    // Waits until there is a frame newer than `after`, the job is final, or `timeout` passes.
    JobSnapshot wait(uint64_t after, std::chrono::milliseconds timeout) const;

    // Queued to running; false, and nothing changed, if the job is not queued (it was cancelled
    // or suspended while it waited).
    bool start();
    // Publishes `frame` as the next frame, in `state` at `progress`. Returns false, and changes
    // nothing, if the job may not move to `state` (it has ended).
    bool publish(JobFrame frame, JobState state, const Progress& progress);
    // Moves to `state` without a picture (a job that never ran: cancelled or suspended while
    // queued, or failed), as the next frame. `before` runs first, under the lock, with the
    // snapshot as it will be (to put it on disk before anyone sees it). Returns false, and
    // changes nothing, if the move is not allowed or the job is not queued and `queued_only`.
    bool end_without_frame(JobState state, const std::string& error, std::optional<StopReason> stop, bool queued_only,
                           const std::function<void(const JobSnapshot&)>& before = {});
    // A resumed job's progress, before it runs again (no new frame).
    void set_progress(const Progress& progress);
    void set_error(const std::string& error);
    void set_stop(std::optional<StopReason> reason);
    void set_parts(const PartCounts& counts);

private:
    mutable std::mutex mutex_;
    mutable std::condition_variable changed_;
    JobSnapshot snapshot_;
};

}  // namespace glint
