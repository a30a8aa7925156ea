// How a job renders: on this server's threads (service/local_runner.h) or on a farm
// (service/farm_runner.h), behind one interface. A runner renders the job's film to the end,
// publishes its frames, writes the store and ends the job's status; the job (service/job.h)
// only starts it, and the job manager decides when.
#pragma once

#include <string>

#include "base/thread_pool.h"
#include "render/renderer.h"
#include "service/frame_publisher.h"
#include "service/job_control.h"
#include "service/job_saver.h"
#include "service/job_status.h"

namespace glint {

// The parts of a job a runner works with; the job owns them and outlives its runner.
struct JobContext {
    const std::string& id;
    RenderJob& render;
    JobStatus& status;
    const FramePublisher& publisher;
    JobSaver& saver;
    const JobControl& control;
    const double& seconds_before;  // rendering time before a restart
};

class JobRunner {
public:
    virtual ~JobRunner() = default;
    // Renders the running job to its end: done, cancelled or failed (or suspended, which ends it
    // in memory while the store keeps it to resume). Never throws.
    virtual void run(ThreadPool& pool) = 0;
    // The job was cancelled before it ran: lets go of anything it still holds elsewhere.
    virtual void cancel_before_start() = 0;
    virtual bool on_farm() const = 0;

protected:
    // Ends the job as failed with `error`: logs it, saves the state, publishes the film as it is.
    static void end_failed(JobContext& job, const std::string& error, const Progress& progress);
    // Ends the job in `state` (done or cancelled) for `reason`: saves its end, then publishes it.
    static void end(JobContext& job, JobState state, StopReason reason, const Progress& progress);
};

}  // namespace glint
