#include "service/job_manager.h"

#include <random>
#include <system_error>

#include <spdlog/spdlog.h>

#include "service/errors.h"
#include "service/slurm_farm.h"

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

JobManager::JobManager(ThreadPool& pool, const ServiceConfig& config, std::unique_ptr<Farm> farm)
    : pool_(pool),
      config_(config),
      store_(config.store.dir.empty() ? nullptr : std::make_unique<JobStore>(config.store)),
      farm_(farm ? std::move(farm) : config.farm.slurm ? std::make_unique<SlurmFarm>(config.farm, config.scenes) : nullptr),
      denoise_gate_(config.max_denoising) {
    try {
        for (unsigned i = 0; i < config_.max_running; ++i) slots_.emplace_back([this] { slot(); });
    } catch (const std::system_error& e) {  // a thread the system refuses: an error, not an abort
        const size_t started = slots_.size();
        shutdown();
        for (std::thread& t : slots_) t.join();
        throw std::runtime_error("cannot start job slot " + std::to_string(started + 1) + " of " +
                                 std::to_string(config_.max_running) + ": " + e.what());
    }
}

JobManager::~JobManager() {
    shutdown();
    for (std::thread& t : slots_) t.join();
}

std::shared_ptr<Job> JobManager::submit(const JobSpec& spec, const std::string& request) {
    const LoadedScene& scene = spec.scene;
    const int priority = spec.priority;
    const uint64_t film_bytes = store_ ? partial_file_size(scene.settings.width, scene.settings.height, scene.settings.aovs) : 0;
    if (store_ && film_bytes > store_->config().limit_bytes)
        throw InvalidRequest("the job's checkpoint (" + std::to_string(film_bytes) +
                             " bytes) would not fit in the store (limit " +
                             std::to_string(store_->config().limit_bytes) + " bytes)");
    if (farm_) check_farm_settings(scene.settings);
    auto job = std::make_shared<Job>(new_job_id(), scene, store_.get(), std::chrono::system_clock::now(),
                                     farm_job(spec.source), priority);
    {
        std::lock_guard lock(mutex_);
        if (stopping_) throw Busy("the server is shutting down");
        if (queue_.size() >= config_.max_queued)
            throw Busy("too many queued jobs (limit " + std::to_string(config_.max_queued) + ")");
        if (store_) {
            try {
                store_->save_request(job->id(), request);
                store_->save_state(job->id(), {job->created(), JobState::queued, "", job->snapshot().progress, priority, {}});
            } catch (const std::exception&) {
                store_->remove(job->id());  // a job the store cannot keep is not accepted
                throw;
            }
        }
        queue_.push_back(job);
        jobs_[job->id()] = job;
        order_.push_back(job->id());
        forget_old_finished(film_bytes);
    }
    work_.notify_one();
    spdlog::info("job {} queued: {}x{}, {} spp, priority {}", job->id(), job->settings().width, job->settings().height,
                 job->settings().spp, priority);
    return job;
}

void JobManager::forget_old_finished(uint64_t reserve) {
    size_t finished = 0;
    for (const auto& id : order_) finished += is_final(jobs_.at(id)->snapshot().state);
    const uint64_t limit = store_ ? store_->config().limit_bytes : 0;
    uint64_t used = store_ ? store_->bytes_used() + reserve : 0;
    for (auto it = order_.begin(); it != order_.end() && (finished > config_.max_finished || used > limit);) {
        if (!is_final(jobs_.at(*it)->snapshot().state)) {
            ++it;
            continue;
        }
        if (store_) {
            const uint64_t bytes = store_->job_bytes(*it);
            store_->remove(*it);
            if (used > limit)
                spdlog::info("store: evicted finished job {} ({} bytes) to keep within the limit of {} bytes", *it,
                             bytes, limit);
            used -= std::min(used, bytes);
        }
        jobs_.erase(*it);
        it = order_.erase(it);
        --finished;
    }
    if (used > limit)
        spdlog::warn("store: {} bytes in use or about to be, over the limit of {} bytes: every job left is unfinished",
                     used, limit);
}

void JobManager::restore(const std::function<JobSpec(const std::string&)>& parse) {
    if (!store_) return;
    std::vector<std::shared_ptr<Job>> restored_jobs;
    for (const StoredJob& stored : store_->load()) {
        try {
            restored_jobs.push_back(restore_job(stored, parse(stored.request)));
        } catch (const std::exception& e) {
            spdlog::error("store: job {} left out: its request is not accepted any more: {}", stored.id, e.what());
        }
    }
    size_t unfinished = 0;
    {
        // All at once: a slot that saw the first restored job queued alone would start it ahead
        // of a later one of higher priority.
        std::lock_guard lock(mutex_);
        for (const auto& job : restored_jobs) {
            jobs_[job->id()] = job;
            order_.push_back(job->id());
            if (is_final(job->snapshot().state)) continue;
            queue_.push_back(job);
            ++unfinished;
        }
        forget_old_finished();
    }
    work_.notify_all();
    const size_t restored = restored_jobs.size();
    spdlog::info("store {}: {} jobs restored, {} of them to resume; {} bytes in use, limit {} bytes",
                 store_->config().dir.string(), restored, unfinished, store_->bytes_used(), store_->config().limit_bytes);
}

std::shared_ptr<Job> JobManager::restore_job(const StoredJob& stored, const JobSpec& spec) const {
    LoadedScene scene = spec.scene;
    const JobRecord& record = stored.record;
    if (scene.settings.time_limit > 0)  // the time rendered before the restart counts
        scene.settings.time_limit = std::max(1e-3, scene.settings.time_limit - record.progress.seconds);
    auto job = std::make_shared<Job>(stored.id, scene, store_.get(), record.created,
                                     farm_job(spec.source, stored.farm), record.priority);
    const bool final = is_final(record.state);
    const FilmFile which = final ? FilmFile::final : FilmFile::checkpoint;
    try {
        if (final) {
            std::optional<Partial> film;
            if (record.state != JobState::failed && store_->has_film(stored.id, which))
                film = store_->load_film(stored.id, which);
            job->restore_final(record, film ? &*film : nullptr);
        } else if (store_->has_film(stored.id, which)) {
            job->resume(store_->load_film(stored.id, which), record.progress);
            spdlog::info("store: job {} resumes from its checkpoint at {} spp", stored.id, job->snapshot().progress.spp_done);
        }
    } catch (const std::exception& e) {
        job->fail(store_->film_path(stored.id, which).string() + ": " + e.what());
    }
    return job;
}

FarmJob JobManager::farm_job(const SceneSource& source, const std::string& stored_run) const {
    if (!farm_) return {};
    FarmJob job{farm_.get(), source, std::nullopt};
    if (!stored_run.empty()) job.run = farm_->resume(nlohmann::json::parse(stored_run));
    return job;
}

void JobManager::slot() {
    for (;;) {
        std::shared_ptr<Job> job;
        {
            std::unique_lock lock(mutex_);
            work_.wait(lock, [&] { return stopping_ || !queue_.empty(); });
            if (stopping_) return;
            job = take_next();
            ++running_;
        }
        job->run(pool_);
        std::lock_guard lock(mutex_);
        --running_;
        // The job's final film replaced its checkpoint. Not while stopping: suspended jobs look
        // ended in memory, but the store keeps them to resume.
        if (store_ && !stopping_) forget_old_finished();
    }
}

// The queued job of highest priority, the earliest submitted among equals. Priorities may change
// while jobs wait (PATCH), so they are read here rather than kept in the queue's order.
std::shared_ptr<Job> JobManager::take_next() {
    auto next = queue_.begin();
    for (auto it = queue_.begin(); it != queue_.end(); ++it)
        if ((*it)->priority() > (*next)->priority()) next = it;
    std::shared_ptr<Job> job = *next;
    queue_.erase(next);
    return job;
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
    for (const auto& job : all) store_ ? job->suspend() : job->cancel();
    spdlog::info("job manager stopped: {} jobs cancelled or finished", all.size());
}

}  // namespace glint
