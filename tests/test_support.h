// Helpers shared by the tests that render whole scenes.
#pragma once

#include <string>

#include "renderer.h"
#include "scene_loader.h"

namespace glint::testing {

inline LoadedScene scene_from(const std::string& json) { return parse_scene(json, {}); }

// Renders a scene on its own pool; the film holds every sample.
inline std::unique_ptr<RenderJob> render(const LoadedScene& loaded, unsigned threads = 2) {
    ThreadPool pool(threads);
    auto job = std::make_unique<RenderJob>(loaded.scene, loaded.settings);
    job->run(pool);
    return job;
}

// The mean of every sample in a block of pixels (channel c), with its standard error: the
// camera samples' rounds pooled (each round's mean one observation), plus the block's average of
// light-tracing splats (their variance taken per pixel, as if the pixels' splats were
// independent).
struct Estimate {
    double mean = 0, sigma = 0;
};
inline Estimate pooled(const Film& film, int c, int x0 = 0, int y0 = 0, int x1 = -1, int y1 = -1) {
    if (x1 < 0) x1 = film.width();
    if (y1 < 0) y1 = film.height();
    double sum = 0, count = 0, round_mean_sq = 0, rounds = 0, splat = 0, splat_var = 0;
    const double spp = film.samples_per_pixel();
    for (int y = y0; y < y1; ++y)
        for (int x = x0; x < x1; ++x) {
            const PixelSums& px = film.pixel(x, y);
            const double k = double(px.count) / double(px.rounds);  // samples per round
            sum += px.sum[c];
            count += double(px.count);
            round_mean_sq += px.round_sq[c] / (k * k);
            rounds += double(px.rounds);
            splat += film.splat_mean(px, spp)[c];
            splat_var += film.splat_variance(px, c, spp);
        }
    const double mean = sum / count, pixels = double(x1 - x0) * (y1 - y0);
    const double var = std::max(0.0, round_mean_sq / rounds - mean * mean) / rounds + splat_var / (pixels * pixels);
    return {mean + splat / pixels, std::sqrt(var)};
}

}  // namespace glint::testing
