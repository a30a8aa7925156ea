// A fixed set of worker threads shared by every job. Callers hand it batches of independent
// tasks; workers take tasks round-robin across the waiting batches, so several jobs rendering
// at once each advance and a small job is not stuck behind a large one.
#pragma once

#include <condition_variable>
#include <cstddef>
#include <deque>
#include <functional>
#include <memory>
#include <mutex>
#include <thread>
#include <vector>

namespace glint {

class ThreadPool {
public:
    // The most threads a command line may ask for (`--threads`): far beyond any machine's cores,
    // low enough that a typo such as 100000 is refused with its range instead of exhausting the
    // process's threads.
    static constexpr unsigned kMaxThreads = 1024;

    // 0 means one per hardware thread. Throws std::runtime_error, with every thread it started
    // joined, when the system refuses a thread (a process or memory limit).
    explicit ThreadPool(unsigned threads);
    ~ThreadPool();
    ThreadPool(const ThreadPool&) = delete;
    ThreadPool& operator=(const ThreadPool&) = delete;

    unsigned size() const { return static_cast<unsigned>(workers_.size()); }
    // Batches with tasks not yet handed out (for monitoring and tests).
    size_t pending_batches() const;

    // Runs task(i) for every i in [0, count) on the workers and returns when all have finished.
    // Must not be called from inside a task (the caller only waits).
    void parallel_for(size_t count, const std::function<void(size_t)>& task);

private:
    struct Batch {
        const std::function<void(size_t)>* task;
        size_t count;
        size_t next = 0;      // next index to hand out
        size_t finished = 0;  // tasks completed
    };
    void work();
    void stop_workers();

    mutable std::mutex mutex_;
    std::condition_variable work_ready_, batch_done_;
    std::deque<std::shared_ptr<Batch>> batches_;  // batches with indices left to hand out
    bool stopping_ = false;
    std::vector<std::thread> workers_;
};

}  // namespace glint
