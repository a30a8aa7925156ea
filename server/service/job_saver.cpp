#include "service/job_saver.h"

#include <algorithm>

#include <spdlog/spdlog.h>

namespace glint {
namespace {

// Samples per pixel of the pixels that got the most: a cancelled pass leaves some tiles ahead.
uint32_t most_samples(const Film& film) {
    uint64_t most = 0;
    for (const PixelSums& px : film.pixels()) most = std::max(most, px.count + px.dropped);
    return uint32_t(most);
}

}  // namespace

JobSaver::JobSaver(const JobStore* store, std::string id, std::chrono::system_clock::time_point created,
                   const std::atomic<int>& priority, uint64_t fingerprint)
    : store_(store), id_(std::move(id)), created_(created), priority_(priority),
      checkpointer_(store ? store->config().checkpoint_interval : 0, fingerprint) {}

JobRecord JobSaver::record(JobState state, const std::string& error, const Progress& progress,
                           std::optional<StopReason> stop) const {
    return {created_, state, error, progress, priority_, stop};
}

void JobSaver::save_state(const JobRecord& record) const {
    if (!store_) return;
    try {
        store_->save_state(id_, record);
    } catch (const std::exception& e) {
        spdlog::error("job {}: cannot save its state: {}", id_, e.what());
    }
}

void JobSaver::checkpoint(const RenderJob& render, const Progress& progress, bool now) {
    if (!store_) return;
    checkpointer_.after_pass(render, [&](const Partial& film) {
        const auto start = std::chrono::steady_clock::now();
        try {
            store_->save_film(id_, FilmFile::checkpoint, film);
            store_->save_state(id_, record(JobState::running, "", progress, std::nullopt));
            spdlog::info("job {} checkpoint at {} spp in {:.1f} ms", id_, progress.spp_done,
                         std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count());
        } catch (const std::exception& e) {
            spdlog::error("job {}: checkpoint failed: {}", id_, e.what());
        }
    }, now);
}

void JobSaver::save_final(const RenderJob& render, JobState state, const Progress& progress,
                          std::optional<StopReason> stop) const {
    if (!store_) return;
    try {
        if (const uint32_t most = most_samples(render.film()); most > 0)
            store_->save_film(id_, FilmFile::final, partial_of(render, checkpointer_.fingerprint(), most));
        store_->save_state(id_, record(state, "", progress, stop));
        std::filesystem::remove(store_->film_path(id_, FilmFile::checkpoint));
    } catch (const std::exception& e) {
        spdlog::error("job {}: cannot save its end: {}", id_, e.what());
    }
}

void JobSaver::save_farm(const FarmRun& run) const {
    if (store_) store_->save_farm(id_, run.to_json().dump());
}

}  // namespace glint
