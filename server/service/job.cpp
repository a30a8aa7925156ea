#include "service/job.h"

#include <algorithm>
#include <cmath>

#include <spdlog/spdlog.h>

#include "denoise/denoiser.h"
#include "assembly/fingerprint.h"
#include "service/errors.h"
#include "service/priority.h"

namespace glint {

namespace {

// Samples per pixel of the pixels that got the most: a cancelled pass leaves some tiles ahead.
uint32_t most_samples(const Film& film) {
    uint64_t most = 0;
    for (const PixelSums& px : film.pixels()) most = std::max(most, px.count + px.dropped);
    return uint32_t(most);
}

}  // namespace

Job::Job(std::string id, const LoadedScene& scene, const JobStore* store, std::chrono::system_clock::time_point created,
         FarmJob farm, int priority)
    : id_(std::move(id)), render_(scene.scene, scene.settings), created_(created), warnings_(scene.warnings), store_(store),
      priority_(priority), farm_(std::move(farm)) {
    render_.set_weight(priority_weight(priority));
    snapshot_.progress.spp_target = render_.settings().spp;
    if (store_ || on_farm()) fingerprint_ = fingerprint(*scene.scene, scene.settings);
}

Progress Job::with_earlier_time(Progress p) const {
    p.seconds += seconds_before_;
    return p;
}

JobRecord Job::record_locked(JobState state, const std::string& error, const Progress& progress) const {
    return {created_, state, error, progress, priority_, snapshot_.stop};
}

JobRecord Job::record(JobState state, const std::string& error, const Progress& progress) const {
    std::lock_guard lock(mutex_);
    return record_locked(state, error, progress);
}

void Job::save_state(JobState state, const std::string& error, const Progress& progress) const {
    if (store_) write_state(record(state, error, progress));
}

void Job::write_state(const JobRecord& record) const {
    try {
        store_->save_state(id_, record);
    } catch (const std::exception& e) {
        spdlog::error("job {}: cannot save its state: {}", id_, e.what());
    }
}

// Called between passes, so the film holds whole passes: resuming from it adds the remaining
// samples in the order an uninterrupted run would.
void Job::checkpoint(const Progress& progress) {
    using Clock = std::chrono::steady_clock;
    const auto interval = std::chrono::duration<double>(store_->config().checkpoint_interval);
    if (!suspended_ && Clock::now() - last_checkpoint_ < interval) return;
    const auto start = Clock::now();
    try {
        store_->save_film(id_, FilmFile::checkpoint, partial_of(render_, fingerprint_, progress.spp_done));
        store_->save_state(id_, record(JobState::running, "", progress));
        spdlog::info("job {} checkpoint at {} spp in {:.1f} ms", id_, progress.spp_done,
                     std::chrono::duration<double, std::milli>(Clock::now() - start).count());
    } catch (const std::exception& e) {
        spdlog::error("job {}: checkpoint failed: {}", id_, e.what());
    }
    last_checkpoint_ = Clock::now();
}

// The final film replaces the checkpoint only once the state says the job ended: a crash in
// between leaves a job that resumes from its checkpoint. Its sample range covers every pixel's
// samples, also those of a pass cut short (which only some pixels have). Called before the job
// ends in memory, so a job is evicted only once its files are complete.
void Job::save_final(JobState state, const Progress& progress) const {
    if (!store_) return;
    try {
        if (const uint32_t most = most_samples(render_.film()); most > 0)
            store_->save_film(id_, FilmFile::final, partial_of(render_, fingerprint_, most));
        store_->save_state(id_, record(state, "", progress));
        std::filesystem::remove(store_->film_path(id_, FilmFile::checkpoint));
    } catch (const std::exception& e) {
        spdlog::error("job {}: cannot save its end: {}", id_, e.what());
    }
}

namespace {

// Each pixel's camera samples over the most any pixel has, as a linear grey PNG.
std::vector<uint8_t> samples_png(const Film& film, uint64_t& most) {
    most = 1;
    for (const PixelSums& px : film.pixels()) most = std::max(most, px.count);
    Image grey(film.width(), film.height());
    for (int y = 0; y < film.height(); ++y)
        for (int x = 0; x < film.width(); ++x)  // gamma 2.2 encoding undone, so grey is linear in count
            grey.set(x, y, Rgb{std::pow(double(film.pixel(x, y).count) / double(most), 2.2)});
    return encode_png(grey, Encoding::gamma22);
}

}  // namespace

void Job::publish(JobState state, const Progress& progress) {
    if (render_.settings().adaptive.on()) {
        uint64_t most = 0;
        auto png = std::make_shared<const std::vector<uint8_t>>(samples_png(render_.film(), most));
        std::lock_guard lock(mutex_);
        snapshot_.samples_png = std::move(png);
        snapshot_.samples_max = most;
    }
    publish_frame(render_.film().mean(), film_layers(render_.film()),
                  std::make_shared<const HalfBuffers>(half_buffers(render_.film())), state, progress, false);
}

// Only the render thread publishes, so the progress read here is still the job's when written.
void Job::publish_preview(const Image& preview) {
    publish_frame(preview, {}, nullptr, JobState::running, snapshot().progress, true);
}

void Job::publish_frame(Image frame, std::vector<ExrLayer> layers, std::shared_ptr<const HalfBuffers> halves,
                        JobState state, const Progress& progress, bool preview) {
    // Encode outside the lock: watchers only ever wait for the pointer swap.
    auto image = std::make_shared<const Image>(std::move(frame));
    auto exr_layers = layers.empty() ? nullptr : std::make_shared<const std::vector<ExrLayer>>(std::move(layers));
    auto png = std::make_shared<const std::vector<uint8_t>>(encode_png(*image, render_.settings().encoding));
    {
        std::lock_guard lock(mutex_);
        snapshot_.frame += 1;
        snapshot_.state = state;
        snapshot_.progress = progress;
        snapshot_.png = std::move(png);
        snapshot_.image = std::move(image);
        snapshot_.layers = std::move(exr_layers);
        snapshot_.halves = std::move(halves);
        snapshot_.preview = preview;
    }
    changed_.notify_all();
}

void Job::set_stop(StopReason reason) {
    std::lock_guard lock(mutex_);
    snapshot_.stop = reason;
}

bool Job::set_priority(int priority) {
    {
        std::lock_guard lock(mutex_);
        if (is_final(snapshot_.state)) return false;
        priority_ = priority;
    }
    render_.set_weight(priority_weight(priority));
    const JobSnapshot s = snapshot();
    save_state(s.state, "", s.progress);
    spdlog::info("job {} priority {}", id_, priority);
    return true;
}

void Job::run(ThreadPool& pool) {
    {
        std::lock_guard lock(mutex_);
        if (snapshot_.state != JobState::queued) return;  // cancelled while queued
        snapshot_.state = JobState::running;
    }
    changed_.notify_all();
    spdlog::info("job {} running{}: {}x{}, {} spp, from sample {}", id_, on_farm() ? " on the farm" : "",
                 settings().width, settings().height, settings().spp, render_.progress().spp_done);
    if (on_farm()) return render_on_farm();
    render_here(pool);
}

void Job::end_failed(const std::string& error, const Progress& progress) {
    spdlog::error("job {} failed: {}", id_, error);
    save_state(JobState::failed, error, progress);
    {
        std::lock_guard lock(mutex_);
        snapshot_.error = error;
    }
    publish(JobState::failed, progress);
}

void Job::render_here(ThreadPool& pool) {
    StopReason reason = StopReason::cancelled;
    try {
        reason = render_.run(pool, [&](const Progress& pass) {
            const Progress p = with_earlier_time(pass);
            publish(JobState::running, p);
            spdlog::info("job {} running: {}/{} spp, error {:.4g}", id_, p.spp_done, p.spp_target, p.error_estimate);
            if (store_) checkpoint(p);
            if (suspended_) render_.cancel();
        }, [&](const Image& preview) { publish_preview(preview); });
        if (suspended_ && reason == StopReason::cancelled) {
            publish(JobState::cancelled, with_earlier_time(render_.progress()));
            spdlog::info("job {} suspended at {} spp: it resumes when the server restarts on the store", id_,
                         render_.progress().spp_done);
            return;
        }
        // The final frame also holds the samples of a pass cut short: nothing rendered is lost.
        const JobState end = reason == StopReason::cancelled ? JobState::cancelled : JobState::done;
        const Progress p = with_earlier_time(render_.progress());
        set_stop(reason);
        save_final(end, p);
        publish(end, p);
    } catch (const std::exception& e) {
        end_failed(e.what(), with_earlier_time(render_.progress()));
        return;
    }
    const JobSnapshot last = snapshot();
    spdlog::info("job {} {} ({}): {} spp in {:.2f} s, error {:.4g}", id_, to_string(last.state), to_string(reason),
                 last.progress.spp_done, last.progress.seconds, last.progress.error_estimate);
}

bool Job::merge_parts(std::vector<PartFilm>& parts) {
    uint32_t samples = 0;
    size_t done = 0, have = 0;
    for (const PartFilm& part : parts) {
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
    Film merged(render_.film().width(), render_.film().height(), render_.settings().aovs);
    if (all_done) {
        std::vector<Partial> films;
        for (PartFilm& part : parts) films.push_back(std::move(*part.film));
        merged = merge_partials(std::move(films)).film;
    } else {
        for (const PartFilm& part : parts)
            if (part.film) merged.merge(part.film->film);
    }
    render_.resume(std::move(merged), samples);
    return all_done;
}

void Job::render_on_farm() {
    const auto start = std::chrono::steady_clock::now();
    const auto progress = [&] {
        Progress p = render_.progress();
        p.seconds = seconds_before_ + std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
        p.samples_per_second =
            p.seconds > 0 ? double(p.spp_done) * render_.film().width() * render_.film().height() / p.seconds : 0;
        return p;
    };
    const SlurmFarm& farm = *farm_.farm;
    try {
        if (!farm_.run) {
            farm_.run = farm.submit(id_, farm_.request, settings());
            if (store_) store_->save_farm(id_, farm_.run->to_json().dump());
            spdlog::info("job {} submitted to Slurm: parts {}, merge {}", id_, farm_.run->array, farm_.run->merge);
        }
        std::vector<PartFilm> parts(farm_.run->ranges.size());
        for (bool done = false; !done;) {
            if (suspended_) return publish(JobState::cancelled, progress());  // the parts go on; a restart follows them
            if (cancelled_) {
                farm.cancel(*farm_.run);
                set_stop(StopReason::cancelled);
                save_final(JobState::cancelled, progress());
                return publish(JobState::cancelled, progress());
            }
            if (const auto failure = farm.failure(*farm_.run)) {
                farm.cancel(*farm_.run);
                return end_failed(*failure, progress());
            }
            const auto look = std::chrono::steady_clock::now();
            bool changed = false;
            for (size_t i = 0; i < parts.size(); ++i) changed |= farm.refresh(*farm_.run, i, parts[i]);
            done = changed && merge_parts(parts);
            if (changed)
                spdlog::info("job {} on the farm: {}/{} spp, parts read and merged in {:.1f} ms", id_,
                             render_.progress().spp_done, settings().spp,
                             std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - look).count());
            const PartCounts counts = farm.count(*farm_.run);
            {
                std::lock_guard lock(mutex_);
                snapshot_.parts = counts;
            }
            if (changed && !done) publish(JobState::running, progress());
            std::unique_lock lock(mutex_);
            changed_.wait_for(lock, std::chrono::duration<double>(farm.config().poll_interval),
                              [&] { return cancelled_ || suspended_; });
        }
        set_stop(StopReason::completed);
        save_final(JobState::done, progress());
        publish(JobState::done, progress());
        spdlog::info("job {} done on the farm: {} spp", id_, render_.progress().spp_done);
    } catch (const std::exception& e) {
        if (farm_.run) farm.cancel(*farm_.run);
        end_failed(e.what(), progress());
    }
}

void Job::cancel() {
    cancelled_ = true;
    {
        std::lock_guard lock(mutex_);
        if (is_final(snapshot_.state) || suspended_) return;
        if (snapshot_.state == JobState::queued) {
            snapshot_.stop = StopReason::cancelled;
            if (store_) write_state(record_locked(JobState::cancelled, "", snapshot_.progress));  // on disk first, as in run()
            snapshot_.state = JobState::cancelled;
            snapshot_.frame += 1;
            // A farm job a restarted server took back: its parts run on though it waits here.
            if (farm_.run) farm_.farm->cancel(*farm_.run);
        }
    }
    render_.cancel();
    changed_.notify_all();
    spdlog::info("job {} cancel requested", id_);
}

void Job::suspend() {
    {
        std::lock_guard lock(mutex_);
        suspended_ = true;
        if (snapshot_.state == JobState::queued) {  // ends in memory only: the store keeps it queued
            snapshot_.state = JobState::cancelled;
            snapshot_.frame += 1;
        }
    }
    changed_.notify_all();
}

void Job::resume(const Partial& checkpoint, const Progress& saved) {
    check_continues(checkpoint, fingerprint_, settings());
    render_.resume(checkpoint.film, checkpoint.end_sample - checkpoint.first_sample);
    seconds_before_ = saved.seconds;
    Progress p = saved;
    p.spp_done = render_.progress().spp_done;
    std::lock_guard lock(mutex_);
    snapshot_.progress = p;
}

void Job::restore_final(const JobRecord& record, const Partial* film) {
    std::shared_ptr<const Image> image;
    std::shared_ptr<const std::vector<uint8_t>> png;
    std::shared_ptr<const HalfBuffers> halves;
    if (film) {
        if (film->fingerprint != fingerprint_ || film->film.width() != render_.film().width() ||
            film->film.height() != render_.film().height())
            throw std::invalid_argument("it is from another scene or settings (fingerprint or size differs)");
        image = std::make_shared<const Image>(film->film.mean());
        png = std::make_shared<const std::vector<uint8_t>>(encode_png(*image, settings().encoding));
        halves = std::make_shared<const HalfBuffers>(half_buffers(film->film));
    }
    std::lock_guard lock(mutex_);
    snapshot_.frame = 1;
    snapshot_.state = record.state;
    snapshot_.error = record.error;
    snapshot_.progress = record.progress;
    snapshot_.stop = record.stop;
    snapshot_.image = std::move(image);
    snapshot_.png = std::move(png);
    snapshot_.halves = std::move(halves);
}

void Job::fail(const std::string& error) {
    save_state(JobState::failed, error, snapshot().progress);
    {
        std::lock_guard lock(mutex_);
        snapshot_.frame += 1;
        snapshot_.state = JobState::failed;
        snapshot_.error = error;
        snapshot_.png.reset();
        snapshot_.image.reset();
        snapshot_.halves.reset();
    }
    changed_.notify_all();
    spdlog::error("job {} failed: {}", id_, error);
}

std::shared_ptr<const std::vector<uint8_t>> Job::denoised_png(DenoiseGate& gate) const {
    const JobSnapshot s = snapshot();
    if (!s.halves) return nullptr;
    {
        std::lock_guard lock(denoised_mutex_);
        if (denoised_frame_ == s.frame && denoised_png_) return denoised_png_;
        if (denoising_) throw Busy("job " + id_ + "'s denoised preview is being made: try again when it is done");
        if (!gate.try_enter())
            throw Busy("the server is already making as many denoised previews as it may at once (" +
                       std::to_string(gate.limit()) + "): try again later");
        denoising_ = true;
    }
    // However the denoiser ends: the place goes back, and a finished frame is kept.
    struct Finish {
        const Job& job;
        DenoiseGate& gate;
        uint64_t frame;
        std::shared_ptr<const std::vector<uint8_t>> png;
        ~Finish() {
            std::lock_guard lock(job.denoised_mutex_);
            job.denoising_ = false;
            gate.leave();
            if (!png) return;
            job.denoised_png_ = png;
            job.denoised_frame_ = frame;
        }
    } finish{*this, gate, s.frame, nullptr};
    ThreadPool pool(0);  // the request's own threads: the render's pool belongs to the render
    finish.png = std::make_shared<const std::vector<uint8_t>>(
        encode_png(denoise(*s.halves, DenoiserConfig{}, pool), settings().encoding));
    return finish.png;
}

JobSnapshot Job::snapshot() const {
    std::lock_guard lock(mutex_);
    return snapshot_;
}

JobSnapshot Job::wait(uint64_t after, std::chrono::milliseconds timeout) const {
    std::unique_lock lock(mutex_);
    changed_.wait_for(lock, timeout, [&] { return snapshot_.frame > after || is_final(snapshot_.state); });
    return snapshot_;
}

}  // namespace glint
