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

void ThreadPool::parallel_for(size_t count, const std::function<void(size_t)>& task,
                              const std::atomic<double>* weight) {
    if (count == 0) return;
    auto batch = std::make_shared<Batch>(Batch{&task, count, weight});
    std::unique_lock lock(mutex_);
    // As if it had just had a turn: it goes after the batches due before its own next turn.
    batch->time = now_ + 1 / weight_of(*batch);
    batch->order = arrivals_++;
    batches_.push_back(batch);
    work_ready_.notify_all();
    batch_done_.wait(lock, [&] { return batch->finished == batch->count; });
}

size_t ThreadPool::pending_batches() const {
    std::lock_guard lock(mutex_);
    return batches_.size();
}

double ThreadPool::weight_of(const Batch& batch) {
    const double w = batch.weight ? batch.weight->load(std::memory_order_relaxed) : 1.0;
    return w > 0 ? w : 1.0;
}

std::shared_ptr<ThreadPool::Batch> ThreadPool::take_turn() {
    auto due = batches_.begin();
    for (auto it = batches_.begin(); it != batches_.end(); ++it)
        if ((*it)->time < (*due)->time || ((*it)->time == (*due)->time && (*it)->order < (*due)->order)) due = it;
    std::shared_ptr<Batch> batch = *due;
    now_ = batch->time;
    batch->time += 1 / weight_of(*batch);
    if (++batch->next == batch->count) batches_.erase(due);
    return batch;
}

void ThreadPool::work() {
    std::unique_lock lock(mutex_);
    for (;;) {
        work_ready_.wait(lock, [&] { return stopping_ || !batches_.empty(); });
        if (batches_.empty()) return;  // stopping, and nothing left to do
        std::shared_ptr<Batch> batch = take_turn();
        const size_t index = batch->next - 1;
        lock.unlock();
        (*batch->task)(index);
        lock.lock();
        if (++batch->finished == batch->count) batch_done_.notify_all();
    }
}

}  // namespace glint
