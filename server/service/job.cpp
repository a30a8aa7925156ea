#include "service/job.h"

#include <spdlog/spdlog.h>

#include "assembly/fingerprint.h"
#include "service/local_runner.h"
#include "service/priority.h"

namespace glint {

Job::Job(std::string id, const LoadedScene& scene, const JobStore* store, std::chrono::system_clock::time_point created,
         FarmJob farm, int priority)
    : id_(std::move(id)), render_(scene.scene, scene.settings), created_(created), warnings_(scene.warnings),
      // Hashing the scene costs a pass over every triangle: only for the films that carry it.
      fingerprint_(store || farm.farm ? fingerprint(*scene.scene, scene.settings) : 0), priority_(priority),
      status_([&] {
          Progress p;
          p.spp_target = scene.settings.spp;
          return p;
      }()),
      publisher_(render_, status_), saver_(store, id_, created, priority_, fingerprint_) {
    render_.set_weight(priority_weight(priority));
    const JobContext context{id_, render_, status_, publisher_, saver_, control_, seconds_before_};
    if (farm.farm) runner_ = std::make_unique<FarmRunner>(context, std::move(farm), fingerprint_);
    else runner_ = std::make_unique<LocalRunner>(context);
}

bool Job::set_priority(int priority) {
    if (is_final(status_.snapshot().state)) return false;
    priority_ = priority;
    render_.set_weight(priority_weight(priority));
    const JobSnapshot s = status_.snapshot();
    saver_.save_state(saver_.record(s.state, "", s.progress, s.stop));
    spdlog::info("job {} priority {}", id_, priority);
    return true;
}

void Job::run(ThreadPool& pool) {
    if (!status_.start()) return;  // cancelled while queued
    spdlog::info("job {} running{}: {}x{}, {} spp, from sample {}", id_, on_farm() ? " on the farm" : "",
                 settings().width, settings().height, settings().spp, render_.progress().spp_done);
    runner_->run(pool);
}

void Job::cancel() {
    control_.cancel();
    if (control_.suspended() || is_final(status_.snapshot().state)) return;
    const bool was_queued = status_.end_without_frame(
        JobState::cancelled, "", StopReason::cancelled, true,
        [&](const JobSnapshot& s) { saver_.save_state(saver_.record(s.state, "", s.progress, s.stop)); });
    if (was_queued) runner_->cancel_before_start();
    render_.cancel();
    spdlog::info("job {} cancel requested", id_);
}

void Job::suspend() {
    control_.suspend();
    // A queued job ends in memory only: the store keeps it queued.
    status_.end_without_frame(JobState::cancelled, "", std::nullopt, true);
}

void Job::resume(const Partial& checkpoint, const Progress& saved) {
    saver_.resume(render_, checkpoint);
    seconds_before_ = saved.seconds;
    Progress p = saved;
    p.spp_done = render_.progress().spp_done;
    status_.set_progress(p);
}

void Job::restore_final(const JobRecord& record, const Partial* film) {
    if (film && (film->fingerprint != fingerprint_ || film->film.width() != render_.film().width() ||
                 film->film.height() != render_.film().height()))
        throw std::invalid_argument("it is from another scene or settings (fingerprint or size differs)");
    status_.set_error(record.error);
    status_.set_stop(record.stop);
    publisher_.publish_restored(film ? &film->film : nullptr, record.state, record.progress);
}

void Job::fail(const std::string& error) {
    status_.end_without_frame(JobState::failed, error, status_.snapshot().stop, false, [&](const JobSnapshot& s) {
        saver_.save_state(saver_.record(JobState::failed, error, s.progress, s.stop));
    });
    spdlog::error("job {} failed: {}", id_, error);
}

std::shared_ptr<const std::vector<uint8_t>> Job::denoised_png(DenoiseGate& gate) const {
    return denoised_.png(status_.snapshot(), settings().encoding, gate, id_);
}

}  // namespace glint
