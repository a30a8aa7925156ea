#include "service/job_status.h"

#include <spdlog/spdlog.h>

namespace glint {

JobStatus::JobStatus(const Progress& progress) { snapshot_.progress = progress; }

JobSnapshot JobStatus::snapshot() const {
    std::lock_guard lock(mutex_);
    return snapshot_;
}

JobSnapshot JobStatus::wait(uint64_t after, std::chrono::milliseconds timeout) const {
    std::unique_lock lock(mutex_);
    changed_.wait_for(lock, timeout, [&] { return snapshot_.frame > after || is_final(snapshot_.state); });
    return snapshot_;
}

bool JobStatus::start() {
    {
        std::lock_guard lock(mutex_);
        if (snapshot_.state != JobState::queued) return false;
        snapshot_.state = JobState::running;
    }
    changed_.notify_all();
    return true;
}

bool JobStatus::publish(JobFrame frame, JobState state, const Progress& progress) {
    {
        std::lock_guard lock(mutex_);
        if (!can_move(snapshot_.state, state)) {
            spdlog::error("a {} job cannot publish a frame as {}", to_string(snapshot_.state), to_string(state));
            return false;
        }
        snapshot_.frame += 1;
        snapshot_.state = state;
        snapshot_.progress = progress;
        snapshot_.png = std::move(frame.png);
        snapshot_.image = std::move(frame.image);
        snapshot_.layers = std::move(frame.layers);
        snapshot_.halves = std::move(frame.halves);
        snapshot_.preview = frame.preview;
        if (frame.samples_png) {
            snapshot_.samples_png = std::move(frame.samples_png);
            snapshot_.samples_max = frame.samples_max;
        }
    }
    changed_.notify_all();
    return true;
}

bool JobStatus::end_without_frame(JobState state, const std::string& error, std::optional<StopReason> stop,
                                  bool queued_only, const std::function<void(const JobSnapshot&)>& before) {
    {
        std::lock_guard lock(mutex_);
        if (!can_move(snapshot_.state, state) || (queued_only && snapshot_.state != JobState::queued)) return false;
        JobSnapshot next = snapshot_;
        next.frame += 1;
        next.state = state;
        next.error = error;
        next.stop = stop;
        next.png.reset();
        next.image.reset();
        next.halves.reset();
        if (before) before(next);
        snapshot_ = std::move(next);
    }
    changed_.notify_all();
    return true;
}

void JobStatus::set_progress(const Progress& progress) {
    std::lock_guard lock(mutex_);
    snapshot_.progress = progress;
}

void JobStatus::set_error(const std::string& error) {
    std::lock_guard lock(mutex_);
    snapshot_.error = error;
}

void JobStatus::set_stop(std::optional<StopReason> reason) {
    std::lock_guard lock(mutex_);
    snapshot_.stop = reason;
}

void JobStatus::set_parts(const PartCounts& counts) {
    std::lock_guard lock(mutex_);
    snapshot_.parts = counts;
}

}  // namespace glint
