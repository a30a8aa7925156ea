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
      film_(settings.window().width(), settings.window().height(), settings.aovs),
      light_tracer_(*scene_, tracer_.strategies(), camera_, settings.filter, settings.width, settings.height,
                    settings.window(), film_),
      direct_view_(*scene_, camera_, settings.filter, settings.width, settings.height, scene_->integrator().direct_view_rays),
      // A pixel's light paths splat anywhere in the image: a window gets every splat a whole
      // render would give it only if every pixel's light paths are traced.
      traced_(tracer_.strategies().light_tracing() ? Region{0, 0, settings.width, settings.height} : settings.window()),
      tile_x0_(traced_.x0 / kTileSize),
      tile_y0_(traced_.y0 / kTileSize),
      tiles_x_((traced_.x1 + kTileSize - 1) / kTileSize - tile_x0_),
      tiles_y_((traced_.y1 + kTileSize - 1) / kTileSize - tile_y0_) {
    const uint32_t round = samples_per_round(settings_.filter);
    settings_.spp = std::max(round, (settings_.spp + round - 1) / round * round);
    if (settings_.first_sample % round != 0)
        throw std::invalid_argument("the first sample must be a multiple of " + std::to_string(round));
    if (settings_.adaptive.on()) adaptive_.emplace(settings_.adaptive, settings_.spp, film_.width(), film_.height());
    counts_light_paths_ = adaptive_ && tracer_.strategies().light_tracing() && !settings_.whole_image();
    if (tracer_.strategies().guiding() && guide_iterations(GuideConfig{}, job_spp()) > 0)
        guide_.emplace(scene_->geometry().bounds());
}

uint32_t RenderJob::job_spp() const {
    const uint32_t round = samples_per_round(settings_.filter);
    const uint32_t spp = settings_.adaptive.job_spp ? settings_.adaptive.job_spp : settings_.spp;
    return (spp + round - 1) / round * round;
}

bool RenderJob::train_guide(ThreadPool& pool) {
    tracer_.set_guide(&*guide_);
    const int iterations = guide_iterations(guide_->config(), job_spp());
    for (int k = 0; k < iterations; ++k) {
        const uint32_t first = (uint32_t(1) << k) - 1, last = (uint32_t(2) << k) - 1;
        pool.parallel_for(size_t(settings_.height), [&](size_t row) {
            if (should_stop()) return;
            for (int x = 0; x < settings_.width; ++x) train_pixel(x, int(row), first, last);
        }, &weight_);
        if (should_stop()) {  // what the iteration recorded is incomplete
            guide_.emplace(scene_->geometry().bounds());
            return false;
        }
        guide_->learn(uint64_t(settings_.width) * uint64_t(settings_.height) * (last - first));
    }
    guide_trained_ = true;
    return true;
}

void RenderJob::train_pixel(int x, int y, uint32_t first, uint32_t last) {
    const uint64_t pixel = uint64_t(y) * settings_.width + x;
    for (uint32_t index = first; index < last; ++index) {
        Rng rng = guide_training_stream(settings_.seed, pixel, index);
        const Ray ray = camera_ray(x, y, index, nullptr, rng);
        tracer_.radiance(ray, rng, kNoLightPath, nullptr, DirectView::gathered, nullptr, &*guide_);
    }
}

std::optional<GuideStats> RenderJob::guide_stats() const {
    if (!guide_trained_) return std::nullopt;
    return guide_->stats();
}

Ray RenderJob::camera_ray(int x, int y, uint32_t index, const double* film, Rng& rng) const {
    const uint32_t sub = index % 4;  // smallpt's subpixel (sx, sy) = (sub mod 2, sub / 2)
    const double u1 = film ? film[0] : rng.uniform(), u2 = film ? film[1] : rng.uniform();
    const double fx = x + filter_offset(settings_.filter, sub & 1, u1);
    const double fy = settings_.height - 1 - y + filter_offset(settings_.filter, sub >> 1, u2);
    const double lens1 = rng.uniform(), lens2 = rng.uniform();
    return camera_.generate(fx, fy, lens1, lens2);
}

RenderJob::CameraSample RenderJob::camera_sample(int x, int y, uint32_t index) const {
    const uint64_t pixel = uint64_t(y) * settings_.width + x;
    CameraSample c{camera_stream(settings_.seed, pixel, index),
                   PixelSampler(settings_.seed, pixel, samples_per_round(settings_.filter)), {}, {},
                   settings_.sampler == Sampler::sobol};
    // The stratified sampler's numbers (sampler.h); the independent sampler draws them all from
    // the sample's stream, as smallpt does.
    if (c.sobol) c.stratified = c.sampler.sample(index);
    c.ray = camera_ray(x, y, index, c.sobol ? c.stratified.film : nullptr, c.rng);
    return c;
}

Rgb RenderJob::sample(int x, int y, uint32_t index, Aov* aov) const {
    const uint64_t pixel = uint64_t(y) * settings_.width + x;
    CameraSample c = camera_sample(x, y, index);
    Rng& rng = c.rng;
    const PixelSampler& sampler = c.sampler;
    const Ray& ray = c.ray;
    const FirstVertexSamples* first = c.first();
    // One light path per camera sample, on its own stream; initialised from trace()'s result in
    // place, where assigning it copied its four vertices (~560 bytes).
    const LightPath light = tracer_.strategies().light_tracing() ? [&] {
        Rng light_rng = light_path_stream(settings_.seed, pixel, index);
        return light_tracer_.trace(light_rng);
    }() : LightPath{};
    if (!direct_view_.splits(x, y)) return tracer_.radiance(ray, rng, light, first, DirectView::gathered, aov);
    return tracer_.radiance(ray, rng, light, first, DirectView::left_out, aov) + direct_view(x, y, index, sampler, rng);
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

Region RenderJob::tile_pixels(size_t tile) const {
    const int x0 = (tile_x0_ + int(tile % tiles_x_)) * kTileSize, y0 = (tile_y0_ + int(tile / tiles_x_)) * kTileSize;
    return intersection({x0, y0, x0 + kTileSize, y0 + kTileSize}, traced_);
}

// Tiles lie on the whole image's grid, so a window's pixels and a whole render's see the same
// tiles; nothing depends on the tiling but the order in which pixels are done.
bool RenderJob::render_tile(size_t tile, uint32_t first, uint32_t last) {
    if (should_stop()) return false;
    const Region pixels = tile_pixels(tile), window = settings_.window();
    // A round at a time: the film takes the error estimate's variance from whole rounds.
    const uint32_t round = samples_per_round(settings_.filter);
    std::array<Rgb, kMaxSamplesPerRound> values;
    std::array<Aov, kMaxSamplesPerRound> aovs;
    const size_t aov_count = settings_.aovs ? round : 0;
    for (int y = pixels.y0; y < pixels.y1; ++y)
        for (int x = pixels.x0; x < pixels.x1; ++x) {
            if (!takes_camera_samples(x, y, window)) {
                // Outside the window, for the splats its light paths leave inside; a stopped
                // pixel's, only where the film counts light paths apart (counts_light_paths_).
                if (!window.contains(x, y) || counts_light_paths_) trace_light_paths(x, y, first, last);
                continue;
            }
            for (uint32_t s = first; s < last; s += round) {
                for (uint32_t i = 0; i < round; ++i) values[i] = sample(x, y, s + i, aov_count ? &aovs[i] : nullptr);
                film_.add_round(x - window.x0, y - window.y0, std::span(values.data(), round),
                                first_replicate(s, round), std::span(aovs.data(), aov_count));
            }
        }
    return true;
}

bool RenderJob::takes_camera_samples(int x, int y, const Region& window) const {
    return window.contains(x, y) && (!adaptive_ || adaptive_->active(x - window.x0, y - window.y0));
}

void RenderJob::start_pass() {
    if (adaptive_) adaptive_->update(film_);
}

void RenderJob::trace_light_paths(int x, int y, uint32_t first, uint32_t last) const {
    const uint64_t pixel = uint64_t(y) * settings_.width + x;
    for (uint32_t index = first; index < last; ++index) {
        Rng rng = light_path_stream(settings_.seed, pixel, index);
        light_tracer_.trace(rng);
    }
}

bool RenderJob::render_pass(ThreadPool& pool, uint32_t first, uint32_t last) {
    if (guide_ && !guide_trained_ && !train_guide(pool)) return false;
    if (direct_view_.active() && !direct_view_decided_) {
        pool.parallel_for(size_t(tiles_x_) * tiles_y_, [&](size_t tile) {
            const Region in = intersection(tile_pixels(tile), settings_.window());
            if (!in.empty()) direct_view_.decide(tracer_, camera_, in.x0, in.y0, in.x1, in.y1);
        }, &weight_);
        direct_view_decided_ = true;
    }
    std::atomic<size_t> skipped{0};
    pool.parallel_for(size_t(tiles_x_) * tiles_y_, [&](size_t tile) {
        if (!render_tile(tile, first, last)) ++skipped;
    }, &weight_);
    return skipped == 0;
}

Progress RenderJob::progress() const {
    Progress p;
    p.spp_done = spp_done_;
    p.spp_target = settings_.spp;
    p.seconds = std::chrono::duration<double>(Clock::now() - start_).count();
    p.pixels = uint64_t(film_.width()) * uint64_t(film_.height());
    p.active_pixels = adaptive_ ? adaptive_->active_pixels() : p.pixels;
    p.mean_spp = adaptive_ ? film_.camera_samples_per_pixel() : double(spp_done_);
    p.samples_per_second = p.seconds > 0 ? (p.mean_spp - mean_spp_at_start_) * double(p.pixels) / p.seconds : 0;
    p.error_estimate = film_.error_estimate();
    p.dropped = film_.dropped();
    return p;
}

// With adaptive sampling a pass ends at the next check (every pass but a last short one is a
// check interval): the mask changes only between passes, so it is decided at the same sample
// counts whatever the timing, and a checkpoint (taken between passes) is always at a check.
uint32_t RenderJob::pass_to_check() const {
    return AdaptiveMask::kCheckInterval - spp_done_ % AdaptiveMask::kCheckInterval;
}

// Passes start at one round of samples, so a first image comes at once, and grow towards about
// half a second each (at most doubling), so progress stays visible without per-pass overhead.
uint32_t RenderJob::next_pass_size(uint32_t previous) const {
    const uint32_t round = samples_per_round(settings_.filter);
    const double seconds = std::chrono::duration<double>(Clock::now() - start_).count();
    const double per_sample = seconds / std::max<double>(1, spp_done_);
    const double wanted = std::min<double>(2.0 * previous, 0.5 / std::max(per_sample, 1e-9));
    const uint32_t size = std::max(round, uint32_t(wanted) / round * round);
    return std::min(adaptive_ ? pass_to_check() : size, settings_.spp - spp_done_);
}

void RenderJob::resume(Film film, uint32_t spp_done) {
    if (film.width() != film_.width() || film.height() != film_.height())
        throw std::invalid_argument("the checkpoint's film is " + std::to_string(film.width()) + "x" +
                                    std::to_string(film.height()) + ", the job's " + std::to_string(film_.width()) +
                                    "x" + std::to_string(film_.height()));
    if (film.has_aovs() != settings_.aovs)
        throw std::invalid_argument(std::string("the checkpoint's film ") + (film.has_aovs() ? "has" : "has no") +
                                    " AOVs, the job " + (settings_.aovs ? "wants them" : "does not"));
    if (spp_done > settings_.spp || spp_done % samples_per_round(settings_.filter) != 0)
        throw std::invalid_argument("the checkpoint's " + std::to_string(spp_done) + " spp do not fit the job's " +
                                    std::to_string(settings_.spp));
    film_ = std::move(film);
    spp_done_ = spp_done;
}

Image RenderJob::preview(ThreadPool& pool) const {
    const Region window = settings_.window();
    Image image(window.width(), window.height());
    const uint32_t index = settings_.first_sample;
    const int rows = (window.height() + kPreviewBlock - 1) / kPreviewBlock;
    pool.parallel_for(size_t(rows), [&](size_t row) {
        const int y0 = window.y0 + int(row) * kPreviewBlock, y1 = std::min(y0 + kPreviewBlock, window.y1);
        for (int x0 = window.x0; x0 < window.x1; x0 += kPreviewBlock) {
            CameraSample c = camera_sample(x0, y0, index);  // the block's path: its top-left pixel's
            Rgb value = tracer_.radiance(c.ray, c.rng, kNoLightPath, c.first());
            if (!is_finite(value)) value = Rgb{0};
            for (int y = y0; y < y1; ++y)
                for (int x = x0; x < std::min(x0 + kPreviewBlock, window.x1); ++x)
                    image.set(x - window.x0, y - window.y0, value);
        }
    }, &weight_);
    return image;
}

StopReason RenderJob::run(ThreadPool& pool, const std::function<void(const Progress&)>& on_pass,
                          const std::function<void(const Image&)>& on_preview) {
    start_ = Clock::now();
    if (on_preview && spp_done_ == 0) on_preview(preview(pool));
    spp_at_start_ = spp_done_;
    mean_spp_at_start_ = adaptive_ ? film_.camera_samples_per_pixel() : double(spp_at_start_);
    if (settings_.time_limit > 0)
        deadline_ = start_ + std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(settings_.time_limit));
    uint32_t pass = adaptive_ ? std::min(pass_to_check(), settings_.spp - spp_done_) : samples_per_round(settings_.filter);
    while (spp_done_ < settings_.spp) {
        // A stopped pass leaves some tiles with more samples than others; each pixel's own
        // count keeps its mean right.
        const uint32_t first = settings_.first_sample + spp_done_;
        start_pass();
        if (!render_pass(pool, first, first + pass)) break;
        spp_done_ += pass;
        if (counts_light_paths_) film_.set_light_paths(spp_done_);
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
