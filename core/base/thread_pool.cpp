#include "base/thread_pool.h"

#include <algorithm>
#include <stdexcept>
#include <string>
#include <system_error>

namespace glint {

ThreadPool::ThreadPool(unsigned threads) {
    if (threads == 0) threads = std::max(1u, std::thread::hardware_concurrency());
    try {
        for (unsigned i = 0; i < threads; ++i) workers_.emplace_back([this] { work(); });
    } catch (const std::system_error& e) {
        // The destructor does not run for a constructor that throws, and a joinable thread
        // destroyed unjoined calls std::terminate: stop the workers already started here.
        const size_t started = workers_.size();
        stop_workers();
        throw std::runtime_error("cannot start render thread " + std::to_string(started + 1) + " of " +
                                 std::to_string(threads) + ": " + e.what());
    }
}

ThreadPool::~ThreadPool() { stop_workers(); }

void ThreadPool::stop_workers() {
    {
        std::lock_guard lock(mutex_);
        stopping_ = true;
    }
    work_ready_.notify_all();
    for (std::thread& t : workers_) t.join();
}

void ThreadPool::parallel_for(size_t count, const std::function<void(size_t)>& task) {
    if (count == 0) return;
    auto batch = std::make_shared<Batch>(Batch{&task, count});
    std::unique_lock lock(mutex_);
    batches_.push_back(batch);
    work_ready_.notify_all();
    batch_done_.wait(lock, [&] { return batch->finished == batch->count; });
}

size_t ThreadPool::pending_batches() const {
    std::lock_guard lock(mutex_);
    return batches_.size();
}

void ThreadPool::work() {
    std::unique_lock lock(mutex_);
    for (;;) {
        work_ready_.wait(lock, [&] { return stopping_ || !batches_.empty(); });
        if (batches_.empty()) return;  // stopping, and nothing left to do
        // Take one index from the front batch, then send that batch to the back of the line.
        std::shared_ptr<Batch> batch = batches_.front();
        batches_.pop_front();
        const size_t index = batch->next++;
        if (batch->next < batch->count) batches_.push_back(batch);
        lock.unlock();
        (*batch->task)(index);
        lock.lock();
        if (++batch->finished == batch->count) batch_done_.notify_all();
    }
}

}  // namespace glint
