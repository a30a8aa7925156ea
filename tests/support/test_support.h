// Helpers shared by the tests that render whole scenes.
#pragma once

#include <string>

#include "assembly/scene_loader.h"
#include "render/renderer.h"

namespace glint::testing {

inline LoadedScene scene_from(const std::string& text) { return parse_scene(text, {}); }

// A scene file of scenes/ at a small size.
inline LoadedScene small_scene(const std::string& file, int width, int height, uint32_t spp) {
    LoadedScene s = load_scene(std::string(GLINT_SCENES_DIR) + "/" + file);
    s.settings.width = width;
    s.settings.height = height;
    s.settings.spp = spp;
    return s;
}

// smallpt's Cornell box from scenes/, at 40×30 pixels and `spp` samples a pixel.
inline LoadedScene small_cornell(uint32_t spp = 64) { return small_scene("cornell.json", 40, 30, spp); }

// Renders a scene on its own pool; the film holds every sample.
inline std::unique_ptr<RenderJob> render(const LoadedScene& loaded, unsigned threads = 2) {
    ThreadPool pool(threads);
    auto job = std::make_unique<RenderJob>(loaded.scene, loaded.settings);
    job->run(pool);
    return job;
}

// The mean of every sample in a block of pixels (channel c), with its standard error: each
// pixel's camera variance from its two halves (Film::camera_variance), plus the block's average
// of light-tracing splats (their variance taken per pixel, as if the pixels' splats were
// independent).
struct Estimate {
    double mean = 0, sigma = 0;
};
inline Estimate pooled(const Film& film, int c, int x0 = 0, int y0 = 0, int x1 = -1, int y1 = -1) {
    if (x1 < 0) x1 = film.width();
    if (y1 < 0) y1 = film.height();
    double sum = 0, count = 0, var = 0, splat = 0;
    const double spp = film.samples_per_pixel();
    for (int y = y0; y < y1; ++y)
        for (int x = x0; x < x1; ++x) {
            const PixelSums& px = film.pixel(x, y);
            sum += px.sum[c];
            count += double(px.count);
            var += Film::camera_variance(px, c) + film.splat_variance(px, c, spp);
            splat += film.splat_mean(px, spp)[c];
        }
    const double pixels = double(x1 - x0) * (y1 - y0);
    return {sum / count + splat / pixels, std::sqrt(var) / pixels};
}

// The error of a render at `spp` against the converged image, measured without a reference: two
// renders with different seeds are independent and both unbiased, so the mean squared difference
// between their images is twice either's MSE, the part that depends on the seed included (what a
// sampler whose dimensions are functions of each other leaves behind). `pairs` pairs are
// averaged; the renders' own error estimates are returned beside it (root mean square).
struct Measured {
    double rmse = 0, estimate = 0;
};
inline Measured measure_by_pairs(LoadedScene s, uint32_t spp, int pairs = 1) {
    s.settings.spp = spp;
    double mse = 0, estimate_sq = 0;
    for (int p = 0; p < 2 * pairs; p += 2) {
        s.settings.seed = uint64_t(p) + 1;
        const auto a = render(s);
        s.settings.seed = uint64_t(p) + 2;
        const auto b = render(s);
        const double d = rmse(a->film().mean(), b->film().mean());
        mse += d * d / 2;
        for (const auto* job : {a.get(), b.get()}) estimate_sq += job->film().error_estimate() * job->film().error_estimate() / 2;
    }
    return {std::sqrt(mse / pairs), std::sqrt(estimate_sq / pairs)};
}

}  // namespace glint::testing
