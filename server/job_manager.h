// Accepts jobs into a bounded queue and runs up to `max_running` at once on the shared render
// pool (whose round-robin keeps a small job from starving behind a large one). Finished jobs are
// kept for their images, the oldest forgotten first beyond `max_finished`.
#pragma once

#include <deque>
#include <map>
#include <memory>
#include <mutex>
#include <stdexcept>
#include <thread>
#include <vector>

#include "job.h"

namespace glint {

struct ServiceLimits {
    unsigned max_running = 4;
    size_t max_queued = 16;
    size_t max_finished = 64;
    size_t max_body_bytes = size_t(16) << 20;
    size_t max_streams = 32;
    SceneLimits scene{.max_dimension = 4096, .max_pixels = int64_t(4096) * 4096, .max_spp = 1u << 16};
};

struct QueueFull : std::runtime_error {
    using std::runtime_error::runtime_error;
};

class JobManager {
public:
    JobManager(ThreadPool& pool, const ServiceLimits& limits);
    ~JobManager();  // cancels everything and waits for the running jobs to stop

    // Throws QueueFull when max_queued jobs are already waiting.
    std::shared_ptr<Job> submit(const LoadedScene& scene);
    std::shared_ptr<Job> find(const std::string& id) const;
    std::vector<std::shared_ptr<Job>> list() const;  // oldest first
    size_t running() const;
    size_t queued() const;
    // Cancels every job and stops taking new ones.
    void shutdown();

private:
    void slot();  // one running job at a time, until shutdown
    void forget_old_finished();

    ThreadPool& pool_;
    ServiceLimits limits_;
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
