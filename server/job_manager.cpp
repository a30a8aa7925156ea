#include "job_manager.h"

#include <random>

#include <spdlog/spdlog.h>

namespace glint {
namespace {

std::string new_job_id() {
    static std::mutex mutex;
    static std::mt19937_64 generator{std::random_device{}()};
    std::lock_guard lock(mutex);
    char id[17];
    std::snprintf(id, sizeof id, "%016llx", static_cast<unsigned long long>(generator()));
    return id;
}

}  // namespace

JobManager::JobManager(ThreadPool& pool, const ServiceLimits& limits) : pool_(pool), limits_(limits) {
    for (unsigned i = 0; i < limits_.max_running; ++i) slots_.emplace_back([this] { slot(); });
}

JobManager::~JobManager() {
    shutdown();
    for (std::thread& t : slots_) t.join();
}

std::shared_ptr<Job> JobManager::submit(const LoadedScene& scene) {
    auto job = std::make_shared<Job>(new_job_id(), scene);
    {
        std::lock_guard lock(mutex_);
        if (stopping_) throw QueueFull("the server is shutting down");
        if (queue_.size() >= limits_.max_queued)
            throw QueueFull("too many queued jobs (limit " + std::to_string(limits_.max_queued) + ")");
        queue_.push_back(job);
        jobs_[job->id()] = job;
        order_.push_back(job->id());
        forget_old_finished();
    }
    work_.notify_one();
    spdlog::info("job {} queued: {}x{}, {} spp", job->id(), job->settings().width, job->settings().height,
                 job->settings().spp);
    return job;
}

void JobManager::forget_old_finished() {
    size_t finished = 0;
    for (const auto& id : order_) finished += is_final(jobs_.at(id)->snapshot().state);
    for (auto it = order_.begin(); it != order_.end() && finished > limits_.max_finished;) {
        if (is_final(jobs_.at(*it)->snapshot().state)) {
            jobs_.erase(*it);
            it = order_.erase(it);
            --finished;
        } else {
            ++it;
        }
    }
}

void JobManager::slot() {
    for (;;) {
        std::shared_ptr<Job> job;
        {
            std::unique_lock lock(mutex_);
            work_.wait(lock, [&] { return stopping_ || !queue_.empty(); });
            if (stopping_) return;
            job = queue_.front();
            queue_.pop_front();
            ++running_;
        }
        job->run(pool_);
        std::lock_guard lock(mutex_);
        --running_;
    }
}

std::shared_ptr<Job> JobManager::find(const std::string& id) const {
    std::lock_guard lock(mutex_);
    const auto it = jobs_.find(id);
    return it == jobs_.end() ? nullptr : it->second;
}

std::vector<std::shared_ptr<Job>> JobManager::list() const {
    std::lock_guard lock(mutex_);
    std::vector<std::shared_ptr<Job>> out;
    for (const auto& id : order_) out.push_back(jobs_.at(id));
    return out;
}

size_t JobManager::running() const {
    std::lock_guard lock(mutex_);
    return running_;
}

size_t JobManager::queued() const {
    std::lock_guard lock(mutex_);
    return queue_.size();
}

void JobManager::shutdown() {
    std::vector<std::shared_ptr<Job>> all;
    {
        std::lock_guard lock(mutex_);
        if (stopping_) return;
        stopping_ = true;
        queue_.clear();
        for (const auto& [id, job] : jobs_) all.push_back(job);
    }
    work_.notify_all();
    for (const auto& job : all) job->cancel();
    spdlog::info("job manager stopped: {} jobs cancelled or finished", all.size());
}

}  // namespace glint
