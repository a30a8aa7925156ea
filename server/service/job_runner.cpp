#include "service/job_runner.h"

#include <spdlog/spdlog.h>

namespace glint {

void JobRunner::end_failed(JobContext& job, const std::string& error, const Progress& progress) {
    spdlog::error("job {} failed: {}", job.id, error);
    job.saver.save_state(job.saver.record(JobState::failed, error, progress, job.status.snapshot().stop));
    job.status.set_error(error);
    job.publisher.publish(JobState::failed, progress);
}

void JobRunner::end(JobContext& job, JobState state, StopReason reason, const Progress& progress) {
    job.status.set_stop(reason);
    job.saver.save_final(job.render, state, progress, reason);
    job.publisher.publish(state, progress);
}

}  // namespace glint
