// A fixed set of worker threads shared by every job. Callers hand it batches of independent
// tasks; workers share their turns among the waiting batches in proportion to the batches'
// weights (stride scheduling: each batch keeps a virtual time that advances by 1 / weight per
// task handed out, and the batch with the earliest time goes next, the oldest on a tie). With
// equal weights that is round-robin: several jobs rendering at once each advance, and a small
// job is not stuck behind a large one; a batch of weight 2 gets twice the turns of one of
// weight 1, and every batch with a weight above 0 keeps getting turns.
#pragma once

#include <atomic>
#include <condition_variable>
#include <cstdint>
#include <cstddef>
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
    // Must not be called from inside a task (the caller only waits). `weight` (> 0; null: 1) is
    // read at every turn, so a caller may change it while the batch runs.
    void parallel_for(size_t count, const std::function<void(size_t)>& task,
                      const std::atomic<double>* weight = nullptr);

private:
    struct Batch {
        const std::function<void(size_t)>* task;
        size_t count;
        const std::atomic<double>* weight;
        double time = 0;      // virtual time of its next turn
        uint64_t order = 0;   // arrival, for ties
        size_t next = 0;      // next index to hand out
        size_t finished = 0;  // tasks completed
    };
    void work();
    // Under mutex_: the waiting batch whose turn it is, advanced past that turn; removed from
    // the waiting ones when this was its last index.
    std::shared_ptr<Batch> take_turn();
    static double weight_of(const Batch& batch);
    void stop_workers();

    mutable std::mutex mutex_;
    std::condition_variable work_ready_, batch_done_;
    std::vector<std::shared_ptr<Batch>> batches_;  // batches with indices left to hand out
    double now_ = 0;                                // virtual time of the last turn
    uint64_t arrivals_ = 0;
    bool stopping_ = false;
    std::vector<std::thread> workers_;
};

}  // namespace glint
