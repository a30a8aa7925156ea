#include "render/renderer.h"

#include <array>
#include <span>
#include <stdexcept>
#include <string>

#include "base/sampling.h"

namespace glint {

const char* to_string(StopReason reason) {
    switch (reason) {
        case StopReason::completed: return "completed";
        case StopReason::target_error: return "target error reached";
        case StopReason::time_limit: return "time limit reached";
        case StopReason::cancelled: return "cancelled";
    }
    return "?";
}

RenderJob::RenderJob(std::shared_ptr<const Scene> scene, const RenderSettings& settings)
    : scene_(std::move(scene)),
      settings_(settings),
      camera_(scene_->camera(), settings.width, settings.height),
      tracer_(*scene_, camera_),
      film_(settings.width, settings.height),
      light_tracer_(*scene_, tracer_.strategies(), camera_, settings.filter, film_),
      direct_view_(*scene_, camera_, settings.filter, settings.width, settings.height, scene_->integrator().direct_view_rays),
      tiles_x_((settings.width + kTileSize - 1) / kTileSize),
      tiles_y_((settings.height + kTileSize - 1) / kTileSize) {
    const uint32_t round = samples_per_round(settings_.filter);
    settings_.spp = std::max(round, (settings_.spp + round - 1) / round * round);
    if (settings_.first_sample % round != 0)
        throw std::invalid_argument("the first sample must be a multiple of " + std::to_string(round));
}

Ray RenderJob::camera_ray(int x, int y, uint32_t index, const double* film, Rng& rng) const {
    const uint32_t sub = index % 4;  // smallpt's subpixel (sx, sy) = (sub mod 2, sub / 2)
    const double u1 = film ? film[0] : rng.uniform(), u2 = film ? film[1] : rng.uniform();
    const double fx = x + filter_offset(settings_.filter, sub & 1, u1);
    const double fy = settings_.height - 1 - y + filter_offset(settings_.filter, sub >> 1, u2);
    const double lens1 = rng.uniform(), lens2 = rng.uniform();
    return camera_.generate(fx, fy, lens1, lens2);
}

Rgb RenderJob::sample(int x, int y, uint32_t index) const {
    const uint64_t pixel = uint64_t(y) * settings_.width + x;
    Rng rng = camera_stream(settings_.seed, pixel, index);
    // The stratified sampler's numbers (sampler.h); the independent sampler draws them all from
    // the sample's stream, as smallpt does.
    const bool sobol = settings_.sampler == Sampler::sobol;
    const PixelSampler sampler(settings_.seed, pixel, samples_per_round(settings_.filter));
    const StratifiedSample stratified = sobol ? sampler.sample(index) : StratifiedSample{};
    const Ray ray = camera_ray(x, y, index, sobol ? stratified.film : nullptr, rng);
    const FirstVertexSamples* first = sobol ? &stratified.first : nullptr;
    // One light path per camera sample, on its own stream; initialised from trace()'s result in
    // place, where assigning it copied its four vertices (~560 bytes).
    const LightPath light = tracer_.strategies().light_tracing() ? [&] {
        Rng light_rng = light_path_stream(settings_.seed, pixel, index);
        return light_tracer_.trace(light_rng);
    }() : LightPath{};
    if (!direct_view_.splits(x, y)) return tracer_.radiance(ray, rng, light, first);
    return tracer_.radiance(ray, rng, light, first, DirectView::left_out) + direct_view(x, y, index, sampler, rng);
}

Rgb RenderJob::direct_view(int x, int y, uint32_t index, const PixelSampler& sampler, Rng& rng) const {
    const uint32_t rays = uint32_t(direct_view_.rays());
    const bool sobol = settings_.sampler == Sampler::sobol;
    Rgb sum{0};
    for (uint32_t k = 0; k < rays; ++k) {
        double film[2];
        if (sobol) sampler.direct_view_film(index, rays, k, film);
        const Ray ray = camera_ray(x, y, index, sobol ? film : nullptr, rng);
        sum += tracer_.radiance(ray, rng, kNoLightPath, nullptr, DirectView::alone);
    }
    return sum / double(rays);
}

bool RenderJob::should_stop() const { return cancelled_ || Clock::now() >= deadline_; }

bool RenderJob::render_tile(size_t tile, uint32_t first, uint32_t last) {
    if (should_stop()) return false;
    const int x0 = int(tile % tiles_x_) * kTileSize, y0 = int(tile / tiles_x_) * kTileSize;
    const int x1 = std::min(x0 + kTileSize, settings_.width), y1 = std::min(y0 + kTileSize, settings_.height);
    // A round at a time: the film takes the error estimate's variance from whole rounds.
    const uint32_t round = samples_per_round(settings_.filter);
    std::array<Rgb, kMaxSamplesPerRound> values;
    for (int y = y0; y < y1; ++y)
        for (int x = x0; x < x1; ++x)
            for (uint32_t s = first; s < last; s += round) {
                for (uint32_t i = 0; i < round; ++i) values[i] = sample(x, y, s + i);
                film_.add_round(x, y, std::span(values.data(), round), first_replicate(s, round));
            }
    return true;
}

bool RenderJob::render_pass(ThreadPool& pool, uint32_t first, uint32_t last) {
    if (direct_view_.active() && !direct_view_decided_) {
        pool.parallel_for(size_t(tiles_x_) * tiles_y_, [&](size_t tile) {
            const int x0 = int(tile % tiles_x_) * kTileSize, y0 = int(tile / tiles_x_) * kTileSize;
            direct_view_.decide(tracer_, camera_, x0, y0, std::min(x0 + kTileSize, settings_.width),
                                std::min(y0 + kTileSize, settings_.height));
        });
        direct_view_decided_ = true;
    }
    std::atomic<size_t> skipped{0};
    pool.parallel_for(size_t(tiles_x_) * tiles_y_, [&](size_t tile) {
        if (!render_tile(tile, first, last)) ++skipped;
    });
    return skipped == 0;
}

Progress RenderJob::progress() const {
    Progress p;
    p.spp_done = spp_done_;
    p.spp_target = settings_.spp;
    p.seconds = std::chrono::duration<double>(Clock::now() - start_).count();
    p.samples_per_second = p.seconds > 0 ? double(spp_done_ - spp_at_start_) * settings_.width * settings_.height / p.seconds : 0;
    p.error_estimate = film_.error_estimate();
    p.dropped = film_.dropped();
    return p;
}

// Passes start at one round of samples, so a first image comes at once, and grow towards about
// half a second each (at most doubling), so progress stays visible without per-pass overhead.
uint32_t RenderJob::next_pass_size(uint32_t previous) const {
    const uint32_t round = samples_per_round(settings_.filter);
    const double seconds = std::chrono::duration<double>(Clock::now() - start_).count();
    const double per_sample = seconds / std::max<double>(1, spp_done_);
    const double wanted = std::min<double>(2.0 * previous, 0.5 / std::max(per_sample, 1e-9));
    const uint32_t size = std::max(round, uint32_t(wanted) / round * round);
    return std::min(size, settings_.spp - spp_done_);
}

void RenderJob::resume(Film film, uint32_t spp_done) {
    if (film.width() != settings_.width || film.height() != settings_.height)
        throw std::invalid_argument("the checkpoint's film is " + std::to_string(film.width()) + "x" +
                                    std::to_string(film.height()) + ", the job's " + std::to_string(settings_.width) +
                                    "x" + std::to_string(settings_.height));
    if (spp_done > settings_.spp || spp_done % samples_per_round(settings_.filter) != 0)
        throw std::invalid_argument("the checkpoint's " + std::to_string(spp_done) + " spp do not fit the job's " +
                                    std::to_string(settings_.spp));
    film_ = std::move(film);
    spp_done_ = spp_done;
}

StopReason RenderJob::run(ThreadPool& pool, const std::function<void(const Progress&)>& on_pass) {
    start_ = Clock::now();
    spp_at_start_ = spp_done_;
    if (settings_.time_limit > 0)
        deadline_ = start_ + std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(settings_.time_limit));
    uint32_t pass = samples_per_round(settings_.filter);
    while (spp_done_ < settings_.spp) {
        // A stopped pass leaves some tiles with more samples than others; each pixel's own
        // count keeps its mean right.
        const uint32_t first = settings_.first_sample + spp_done_;
        if (!render_pass(pool, first, first + pass)) break;
        spp_done_ += pass;
        const Progress p = progress();
        if (on_pass) on_pass(p);
        if (settings_.target_error > 0 && p.error_estimate <= settings_.target_error) return StopReason::target_error;
        if (should_stop()) break;
        if (spp_done_ < settings_.spp) pass = next_pass_size(pass);
    }
    if (spp_done_ == settings_.spp) return StopReason::completed;
    return cancelled_ ? StopReason::cancelled : StopReason::time_limit;
}

}  // namespace glint
