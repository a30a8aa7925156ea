#include "service/local_runner.h"

#include <spdlog/spdlog.h>

namespace glint {

Progress LocalRunner::with_earlier_time(Progress p) const {
    p.seconds += job_.seconds_before;
    return p;
}

void LocalRunner::after_pass(const Progress& pass) {
    const Progress p = with_earlier_time(pass);
    job_.publisher.publish(JobState::running, p);
    spdlog::info("job {} running: {}/{} spp, error {:.4g}", job_.id, p.spp_done, p.spp_target, p.error_estimate);
    job_.saver.checkpoint(job_.render, p, job_.control.suspended());
    if (job_.control.suspended()) job_.render.cancel();
}

void LocalRunner::run(ThreadPool& pool) {
    StopReason reason = StopReason::cancelled;
    try {
        reason = job_.render.run(pool, [&](const Progress& pass) { after_pass(pass); },
                                 [&](const Image& preview) { job_.publisher.publish_preview(preview); });
        const Progress p = with_earlier_time(job_.render.progress());
        if (job_.control.suspended() && reason == StopReason::cancelled) {
            job_.publisher.publish(JobState::cancelled, p);
            spdlog::info("job {} suspended at {} spp: it resumes when the server restarts on the store", job_.id,
                         p.spp_done);
            return;
        }
        // The final frame also holds the samples of a pass cut short: nothing rendered is lost.
        end(job_, reason == StopReason::cancelled ? JobState::cancelled : JobState::done, reason, p);
    } catch (const std::exception& e) {
        end_failed(job_, e.what(), with_earlier_time(job_.render.progress()));
        return;
    }
    const JobSnapshot last = job_.status.snapshot();
    spdlog::info("job {} {} ({}): {} spp in {:.2f} s, error {:.4g}", job_.id, to_string(last.state), to_string(reason),
                 last.progress.spp_done, last.progress.seconds, last.progress.error_estimate);
}

}  // namespace glint
