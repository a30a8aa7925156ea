#include "service/farm_runner.h"

#include <spdlog/spdlog.h>

namespace glint {

Progress FarmRunner::progress() const {
    Progress p = job_.render.progress();
    p.seconds = job_.seconds_before + std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
    const Film& film = job_.render.film();
    p.samples_per_second = p.seconds > 0 ? double(p.spp_done) * film.width() * film.height() / p.seconds : 0;
    return p;
}

void FarmRunner::submit() {
    if (farm_.run) return;
    farm_.run = farm_.farm->submit(job_.id, farm_.source, job_.render.settings());
    job_.saver.save_farm(*farm_.run);
    spdlog::info("job {} submitted to the farm: parts {}, merge {}", job_.id, farm_.run->array, farm_.run->merge);
}

bool FarmRunner::merge_parts(std::vector<PartState>& parts) {
    uint32_t samples = 0;
    size_t done = 0, have = 0;
    for (const PartState& part : parts) {
        if (!part.film) continue;
        if (part.film->fingerprint != fingerprint_)
            throw FarmError("a part rendered another scene or settings (fingerprint differs)");
        samples += part.film->end_sample - part.film->first_sample;
        done += part.done;
        ++have;
    }
    if (have == 0) return false;
    const bool all_done = done == parts.size();
    // Every part done: the ranges tile the job, and merge_partials adds them in the order glint
    // merge does, to the whole render's bytes. Before, a preview: the parts' sums so far, added
    // to an empty film (adding to zero is exact) without copying the parts.
    const Film& film = job_.render.film();
    Film merged(film.width(), film.height(), job_.render.settings().aovs);
    if (all_done) {
        std::vector<Partial> films;
        for (PartState& part : parts) films.push_back(std::move(*part.film));
        merged = merge_partials(std::move(films)).film;
    } else {
        for (const PartState& part : parts)
            if (part.film) merged.merge(part.film->film);
    }
    job_.render.resume(std::move(merged), samples);
    return all_done;
}

bool FarmRunner::poll(std::vector<PartState>& parts) {
    const auto look = std::chrono::steady_clock::now();
    const FarmPoll found = farm_.farm->poll(*farm_.run, parts);
    if (found.failure) throw FarmError(*found.failure);
    const bool done = found.films_changed && merge_parts(parts);
    if (found.films_changed)
        spdlog::info("job {} on the farm: {}/{} spp, parts read and merged in {:.1f} ms", job_.id,
                     job_.render.progress().spp_done, job_.render.settings().spp,
                     std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - look).count());
    job_.status.set_parts(found.counts);
    if (found.films_changed && !done) job_.publisher.publish(JobState::running, progress());
    return done;
}

bool FarmRunner::follow() {
    std::vector<PartState> parts(farm_.run->ranges.size());
    for (;;) {
        if (job_.control.suspended()) return false;
        if (job_.control.cancelled()) {
            farm_.farm->cancel(*farm_.run);
            end(job_, JobState::cancelled, StopReason::cancelled, progress());
            return true;
        }
        if (poll(parts)) break;
        job_.control.sleep(farm_.farm->poll_interval());
    }
    end(job_, JobState::done, StopReason::completed, progress());
    spdlog::info("job {} done on the farm: {} spp", job_.id, job_.render.progress().spp_done);
    return true;
}

void FarmRunner::run(ThreadPool&) {
    start_ = std::chrono::steady_clock::now();
    try {
        submit();
        // Suspended: the parts go on, and a restarted server follows them again.
        if (!follow()) job_.publisher.publish(JobState::cancelled, progress());
    } catch (const std::exception& e) {
        if (farm_.run) farm_.farm->cancel(*farm_.run);
        end_failed(job_, e.what(), progress());
    }
}

// A farm job a restarted server took back: its parts run on though it waits here.
void FarmRunner::cancel_before_start() {
    if (farm_.run) farm_.farm->cancel(*farm_.run);
}

}  // namespace glint
