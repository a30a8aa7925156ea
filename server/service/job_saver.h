// One job's writes to the store (service/job_store.h): its state when it changes, its film at
// checkpoints and when it ends, and its farm submission. A write that fails is logged: it never
// stops the render or a request. Without a store, nothing is written.
#pragma once

#include <atomic>
#include <chrono>
#include <optional>
#include <string>

#include "render/renderer.h"
#include "service/checkpointer.h"
#include "service/farm.h"
#include "service/job_store.h"

namespace glint {

class JobSaver {
public:
    // `priority` is the job's, read at each write (it may change while the job runs).
    JobSaver(const JobStore* store, std::string id, std::chrono::system_clock::time_point created,
             const std::atomic<int>& priority, uint64_t fingerprint);

    bool active() const { return store_ != nullptr; }
    // The job's state.json as it would be in `state`.
    JobRecord record(JobState state, const std::string& error, const Progress& progress,
                     std::optional<StopReason> stop) const;
    void save_state(const JobRecord& record) const;
    // After a pass: the film of its whole passes and the running state, at most every checkpoint
    // interval (or `now`), so that a resumed job adds the remaining samples in the order an
    // uninterrupted run would.
    void checkpoint(const RenderJob& render, const Progress& progress, bool now);
    // The job's end: its final film, then its state. The final film replaces the checkpoint
    // only once the state says the job ended, so a crash in between leaves a job that resumes
    // from its checkpoint. Its sample range covers every pixel's samples, also those of a pass
    // cut short (which only some pixels have).
    void save_final(const RenderJob& render, JobState state, const Progress& progress,
                    std::optional<StopReason> stop) const;
    void save_farm(const FarmRun& run) const;
    // Continues `render` from the store's checkpoint `saved`; throws std::invalid_argument if it
    // is not this job's.
    void resume(RenderJob& render, const Partial& saved) const { checkpointer_.resume(render, saved); }

private:
    const JobStore* store_;
    std::string id_;
    std::chrono::system_clock::time_point created_;
    const std::atomic<int>& priority_;
    Checkpointer checkpointer_;
};

}  // namespace glint
