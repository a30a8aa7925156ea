#include "job.h"

#include <spdlog/spdlog.h>

namespace glint {

const char* to_string(JobState state) {
    switch (state) {
        case JobState::queued: return "queued";
        case JobState::running: return "running";
        case JobState::done: return "done";
        case JobState::cancelled: return "cancelled";
        case JobState::failed: return "failed";
    }
    return "?";
}

Job::Job(std::string id, const LoadedScene& scene)
    : id_(std::move(id)), render_(scene.scene, scene.settings), created_(std::chrono::system_clock::now()) {
    snapshot_.progress.spp_target = render_.settings().spp;
}

void Job::publish(JobState state, const Progress& progress) {
    // Encode outside the lock: watchers only ever wait for the pointer swap.
    auto image = std::make_shared<const Image>(render_.film().mean());
    auto png = std::make_shared<const std::vector<uint8_t>>(encode_png(*image, render_.settings().encoding));
    {
        std::lock_guard lock(mutex_);
        snapshot_.frame += 1;
        snapshot_.state = state;
        snapshot_.progress = progress;
        snapshot_.png = std::move(png);
        snapshot_.image = std::move(image);
    }
    changed_.notify_all();
}

void Job::run(ThreadPool& pool) {
    {
        std::lock_guard lock(mutex_);
        if (snapshot_.state != JobState::queued) return;  // cancelled while queued
        snapshot_.state = JobState::running;
    }
    changed_.notify_all();
    spdlog::info("job {} running: {}x{}, {} spp", id_, settings().width, settings().height, settings().spp);
    StopReason reason = StopReason::cancelled;
    try {
        reason = render_.run(pool, [&](const Progress& p) {
            publish(JobState::running, p);
            spdlog::info("job {} running: {}/{} spp, error {:.4g}", id_, p.spp_done, p.spp_target, p.error_estimate);
        });
        // The final frame also holds the samples of a pass cut short: nothing rendered is lost.
        publish(reason == StopReason::cancelled ? JobState::cancelled : JobState::done, render_.progress());
    } catch (const std::exception& e) {
        spdlog::error("job {} failed: {}", id_, e.what());
        publish(JobState::failed, render_.progress());
        return;
    }
    const JobSnapshot last = snapshot();
    spdlog::info("job {} {} ({}): {} spp in {:.2f} s, error {:.4g}", id_, to_string(last.state), to_string(reason),
                 last.progress.spp_done, last.progress.seconds, last.progress.error_estimate);
}

void Job::cancel() {
    {
        std::lock_guard lock(mutex_);
        if (is_final(snapshot_.state)) return;
        if (snapshot_.state == JobState::queued) {
            snapshot_.state = JobState::cancelled;
            snapshot_.frame += 1;
        }
    }
    render_.cancel();
    changed_.notify_all();
    spdlog::info("job {} cancel requested", id_);
}

JobSnapshot Job::snapshot() const {
    std::lock_guard lock(mutex_);
    return snapshot_;
}

JobSnapshot Job::wait(uint64_t after, std::chrono::milliseconds timeout) const {
    std::unique_lock lock(mutex_);
    changed_.wait_for(lock, timeout, [&] { return snapshot_.frame > after || is_final(snapshot_.state); });
    return snapshot_;
}

nlohmann::json Job::status() const {
    const JobSnapshot s = snapshot();
    const Progress& p = s.progress;
    const bool active = s.state == JobState::running && p.spp_done > 0;
    const double eta = active ? p.seconds * (p.spp_target - p.spp_done) / p.spp_done : 0;
    nlohmann::json j = {
        {"id", id_},
        {"state", to_string(s.state)},
        {"width", settings().width},
        {"height", settings().height},
        {"spp_done", p.spp_done},
        {"spp_target", p.spp_target},
        {"elapsed", p.seconds},
        {"samples_per_second", p.samples_per_second},
        {"error_estimate", std::isfinite(p.error_estimate) ? nlohmann::json(p.error_estimate) : nlohmann::json()},
        {"eta", eta},
        {"dropped_samples", p.dropped},
        {"frame", s.frame},
        {"urls", {{"self", "/jobs/" + id_},
                  {"png", "/jobs/" + id_ + "/image.png"},
                  {"pfm", "/jobs/" + id_ + "/image.pfm"},
                  {"stream", "/jobs/" + id_ + "/stream"},
                  {"events", "/jobs/" + id_ + "/events"}}},
    };
    return j;
}

}  // namespace glint
