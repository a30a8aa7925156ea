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

// The mean of every sample in a block of pixels (channel c), with its standard error.
struct Estimate {
    double mean = 0, sigma = 0;
};
inline Estimate pooled(const Film& film, int c, int x0 = 0, int y0 = 0, int x1 = -1, int y1 = -1) {
    if (x1 < 0) x1 = film.width();
    if (y1 < 0) y1 = film.height();
    double sum = 0, sum_sq = 0, n = 0;
    for (int y = y0; y < y1; ++y)
        for (int x = x0; x < x1; ++x) {
            sum += film.pixel(x, y).sum[c];
            sum_sq += film.pixel(x, y).sum_sq[c];
            n += double(film.pixel(x, y).count);
        }
    const double mean = sum / n;
    return {mean, std::sqrt(std::max(0.0, sum_sq / n - mean * mean) / n)};
}

}  // namespace glint::testing
