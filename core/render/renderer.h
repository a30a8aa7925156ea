// Progressive rendering: a job renders its image in passes of whole samples per pixel on a
// shared thread pool, reporting after each pass, until it reaches its sample count, its target
// error estimate or its time limit, or is cancelled.
#pragma once

#include <atomic>
#include <chrono>
#include <functional>
#include <memory>
#include <optional>

#include "scene/camera.h"
#include "render/adaptive_mask.h"
#include "render/direct_view.h"
#include "render/film.h"
#include "render/filter.h"
#include "render/integrator.h"
#include "render/light_tracer.h"
#include "render/path_guide.h"
#include "render/sampler.h"
#include "render/settings.h"
#include "base/thread_pool.h"

namespace glint {

struct Progress {
    // Sample indices done: what every pixel has, or with adaptive sampling, what the pixels still
    // active have (the most any pixel has); a stopped pixel keeps the count it stopped at.
    uint32_t spp_done = 0;
    uint32_t spp_target = 0;
    double mean_spp = 0;  // camera samples taken per pixel on average (spp_done unless adaptive)
    uint64_t pixels = 0, active_pixels = 0;  // of the film; those that still receive samples
    double seconds = 0;
    double samples_per_second = 0;
    double error_estimate = kInfinity;
    uint64_t dropped = 0;  // samples left out: whole rounds with a NaN or infinite sample
};

enum class StopReason { completed, target_error, time_limit, cancelled };
const char* to_string(StopReason reason);

class RenderJob {
public:
    RenderJob(std::shared_ptr<const Scene> scene, const RenderSettings& settings);

    // Renders until a stop condition, calling on_pass after every pass (from this thread). With
    // on_preview, a job that starts from no samples first shows preview() through it.
    StopReason run(ThreadPool& pool, const std::function<void(const Progress&)>& on_pass = {},
                   const std::function<void(const Image&)>& on_preview = {});
    // Thread-safe: the pass in progress stops after the tiles already being rendered.
    void cancel() { cancelled_ = true; }
    // Thread-safe: the job's share of the pool's turns against other jobs' (thread_pool.h).
    void set_weight(double weight) { weight_ = weight; }

    // A first look at the image, at a sixteenth of the cost of a first pass of the tent
    // filter's four samples: one camera path per block of kPreviewBlock² pixels, without light
    // tracing. Thrown away once shown: the film never sees it.
    Image preview(ThreadPool& pool) const;
    // Continues from a checkpoint taken between passes: `film` holds samples [first_sample,
    // first_sample + spp_done) of every pixel, added in sample order, so run() adds the rest in
    // the order an uninterrupted run would and the sums come out bit-identical. Call before
    // run(); throws std::invalid_argument if the film or the count does not fit this job.
    void resume(Film film, uint32_t spp_done);

    // Samples [first, last) of every pixel, added to the film in sample order, a round at a time
    // (both multiples of samples_per_round). Returns false if the job was stopped (cancelled or
    // out of time) before every tile was rendered.
    bool render_pass(ThreadPool& pool, uint32_t first, uint32_t last);

    const Film& film() const { return film_; }
    // The path guide's size once trained (guiding on, and a job long enough to train it).
    std::optional<GuideStats> guide_stats() const;
    const RenderSettings& settings() const { return settings_; }
    Progress progress() const;

private:
    using Clock = std::chrono::steady_clock;
    static constexpr int kTileSize = 16;
    static constexpr int kPreviewBlock = 2;

    // The start of sample `index` of pixel (x, y): its stream, its sampler's numbers and its
    // camera ray, as both the sample and the preview take them.
    struct CameraSample {
        Rng rng;
        PixelSampler sampler;
        StratifiedSample stratified;
        Ray ray;
        bool sobol;
        const FirstVertexSamples* first() const { return sobol ? &stratified.first : nullptr; }
    };
    CameraSample camera_sample(int x, int y, uint32_t index) const;
    // Sample `index` of pixel (x, y); `aov`, if given, receives its AOVs.
    Rgb sample(int x, int y, uint32_t index, Aov* aov) const;
    // The direct view of pixel (x, y) for sample `index` from direct_view_.rays() camera rays.
    Rgb direct_view(int x, int y, uint32_t index, const PixelSampler& sampler, Rng& rng) const;
    // A camera ray for sample `index` of pixel (x, y), through the film position `film` picks in
    // the sample's subpixel (nullptr: two numbers from rng pick it), and a lens point from rng.
    Ray camera_ray(int x, int y, uint32_t index, const double* film, Rng& rng) const;
    // The pixels of tile `tile` (of tiles_x_ × tiles_y_ over traced_).
    Region tile_pixels(size_t tile) const;
    bool render_tile(size_t tile, uint32_t first, uint32_t last);
    // Samples [first, last) of pixel (x, y) outside the window: their light paths only, for
    // the splats they leave in the window.
    void trace_light_paths(int x, int y, uint32_t first, uint32_t last) const;
    bool should_stop() const;
    uint32_t next_pass_size(uint32_t previous) const;
    uint32_t pass_to_check() const;
    // Whether pixel (x, y) of the image takes camera samples in this pass.
    bool takes_camera_samples(int x, int y, const Region& window) const;
    // Before each pass: the adaptive mask from the film (passes then start at its checks).
    void start_pass();
    // Trains the path guide before the film's first sample, from paths of its own: iteration k
    // traces paths [2^k - 1, 2^(k+1) - 1) of every pixel of the image, whatever the window, so
    // every part of a job, a resumed job and a region job learn the guide a whole render learns.
    // False if the job was stopped first; the guide then starts again at the next pass.
    bool train_guide(ThreadPool& pool);
    void train_pixel(int x, int y, uint32_t first, uint32_t last);
    // The whole job's samples per pixel (the training's budget): a part's job's, or spp.
    uint32_t job_spp() const;

    std::shared_ptr<const Scene> scene_;
    RenderSettings settings_;
    Camera camera_;
    PathTracer tracer_;
    Film film_;
    LightTracer light_tracer_;
    DirectViewSplit direct_view_;
    std::optional<AdaptiveMask> adaptive_;  // when settings_.adaptive.on()
    std::optional<PathGuide> guide_;        // when guiding is on and the job trains it
    bool guide_trained_ = false;
    // Light paths are traced apart from camera samples, and counted in the film: an adaptive
    // region job with light tracing. Every light path is an independent path from the lights,
    // whichever pixel's stream it draws from, so the splats need only be divided by the light
    // paths traced per pixel of the image. A whole image traces one with each camera sample, and
    // a stopped pixel traces none, so the film's camera samples per pixel count them exactly; a
    // region job traces every sample's light paths outside the window, so its stopped pixels
    // trace theirs too, and the film counts spp_done per pixel.
    bool counts_light_paths_ = false;
    bool direct_view_decided_ = false;
    Region traced_;  // the pixels whose samples are traced: the window, or with light tracing all
    int tile_x0_, tile_y0_, tiles_x_, tiles_y_;
    uint32_t spp_done_ = 0;
    uint32_t spp_at_start_ = 0;  // samples resumed from, left out of the rate
    double mean_spp_at_start_ = 0;
    std::atomic<bool> cancelled_{false};
    std::atomic<double> weight_{1};
    Clock::time_point start_{}, deadline_ = Clock::time_point::max();
};

}  // namespace glint
