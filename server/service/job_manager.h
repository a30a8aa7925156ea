// Accepts jobs into a bounded queue and runs up to `max_running` at once on the shared render
// pool, highest priority first; running jobs share the pool's turns by their priorities'
// weights, so a small job is not starved behind a large one (service/priority.h). Finished jobs are
// kept for their images, the oldest forgotten first beyond `max_finished` or, with a store,
// beyond the store's size limit (running and queued jobs are never evicted).
#pragma once

#include <condition_variable>
#include <deque>
#include <functional>
#include <map>
#include <memory>
#include <mutex>
#include <thread>
#include <vector>

#include "service/farm.h"
#include "service/job.h"
#include "service/job_spec.h"
#include "service/job_store.h"
#include "service/service_config.h"

namespace glint {

class JobManager {
public:
    // With config.store.dir set, jobs are kept in that folder (job_store.h); call restore() next.
    // Jobs render on `farm` if one is given, else on config.farm's (with config.farm.slurm),
    // else on `pool`.
    JobManager(ThreadPool& pool, const ServiceConfig& config, std::unique_ptr<Farm> farm = nullptr);
    ~JobManager();  // cancels everything and waits for the running jobs to stop

    // Throws Busy (service/errors.h) when max_queued jobs are already waiting or the manager is
    // shutting down, InvalidRequest when the job's film would not fit in the store or it asks a
    // farm for what a farm does not do (service/farm.h). `request` is what the store keeps to
    // rebuild the job after a restart (parsed again by restore's `parse`). Queued jobs start in
    // order of priority (service/priority.h), then of submission.
    std::shared_ptr<Job> submit(const JobSpec& spec, const std::string& request = "");
    // Takes back the store's jobs (same ids, oldest first): unfinished ones are queued to resume
    // from their checkpoints, finished ones serve their images again. A job whose checkpoint is
    // corrupt or does not fit its scene is marked failed with the reason.
    void restore(const std::function<JobSpec(const std::string& request)>& parse);
    std::shared_ptr<Job> find(const std::string& id) const;
    std::vector<std::shared_ptr<Job>> list() const;  // oldest first
    size_t running() const;
    size_t queued() const;
    // Bounds the denoised previews made at once (config.max_denoising): Job::denoised_png's.
    DenoiseGate& denoise_gate() { return denoise_gate_; }
    // Cancels every job and stops taking new ones; with a store, unfinished jobs are suspended
    // instead, to resume on restart.
    void shutdown();

private:
    void slot();  // one running job at a time, until shutdown
    std::shared_ptr<Job> take_next();  // under mutex_, from a queue that is not empty
    // Under mutex_: forgets the oldest finished jobs beyond max_finished or while the store,
    // plus `reserve` bytes about to be written, is over its limit.
    void forget_old_finished(uint64_t reserve = 0);
    std::shared_ptr<Job> restore_job(const StoredJob& stored, const JobSpec& spec) const;
    FarmJob farm_job(const SceneSource& source, const std::string& stored_run = "") const;

    ThreadPool& pool_;
    ServiceConfig config_;
    std::unique_ptr<JobStore> store_;
    std::unique_ptr<Farm> farm_;  // every job renders there, if set
    DenoiseGate denoise_gate_;
    mutable std::mutex mutex_;
    std::condition_variable work_;
    std::deque<std::shared_ptr<Job>> queue_;
    std::map<std::string, std::shared_ptr<Job>> jobs_;
    std::vector<std::string> order_;  // ids in submission order
    size_t running_ = 0;
    bool stopping_ = false;
    std::vector<std::thread> slots_;
};

}  // namespace glint
