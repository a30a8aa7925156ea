// The most any adaptive sampler could gain on a scene: how much sooner the best possible split
// of samples among its pixels reaches the RMSE that plain sampling reaches, every sample costing
// the same. With σᵢ² pixel i's variance per sample (summed over channels) and nᵢ its samples,
// the MSE is Σ σᵢ²/nᵢ over the pixels; for a total of N samples it is least with nᵢ ∝ σᵢ, and
// then (Σ σᵢ)²/N against P·Σ σᵢ²/N for N/P samples everywhere, so the bound is
// P·Σ σᵢ² / (Σ σᵢ)². σᵢ² is measured across --seeds independent renders of --spp samples each
// (their spread, not a film's halves: 3·(seeds − 1) degrees of freedom a pixel, so the noise of
// the estimate barely raises the bound). Prints one CSV row: scene, seeds, spp, bound.
#include <CLI/CLI.hpp>

#include <cmath>
#include <cstdio>
#include <filesystem>

#include "assembly/scene_loader.h"
#include "render/renderer.h"

using namespace glint;

int main(int argc, char** argv) {
    std::string scene;
    int width = 128, height = 96;
    uint32_t seeds = 32, spp = 32;
    unsigned threads = 2;
    CLI::App app{"The largest time gain any per-pixel split of samples can give at equal RMSE"};
    app.add_option("scene", scene, "Scene JSON")->required();
    app.add_option("--width", width);
    app.add_option("--height", height);
    app.add_option("--seeds", seeds, "Independent renders the variances are measured across")->check(CLI::Range(2, 1024));
    app.add_option("--spp", spp, "Samples per pixel of each");
    app.add_option("--threads", threads);
    CLI11_PARSE(app, argc, argv);
    LoadedScene loaded = load_scene(scene);
    loaded.settings.width = width;
    loaded.settings.height = height;
    loaded.settings.spp = spp;
    const size_t values = size_t(width) * height * 3;
    std::vector<double> sum(values), sum_sq(values);
    ThreadPool pool(threads);
    for (uint32_t s = 0; s < seeds; ++s) {
        loaded.settings.seed = 1000 + s;
        RenderJob job(loaded.scene, loaded.settings);
        job.render_pass(pool, 0, spp);
        const Image mean = job.film().mean();
        for (size_t i = 0; i < values; ++i) sum[i] += mean.rgb[i], sum_sq[i] += double(mean.rgb[i]) * mean.rgb[i];
    }
    double sigma = 0, variance = 0;
    for (size_t p = 0; p < values / 3; ++p) {
        double v = 0;  // per sample, summed over the channels
        for (size_t i = p * 3; i < p * 3 + 3; ++i) v += (sum_sq[i] - sum[i] * sum[i] / seeds) / (seeds - 1) * spp;
        sigma += std::sqrt(std::max(0.0, v));
        variance += std::max(0.0, v);
    }
    std::printf("%s,%u,%u,%.4f\n", std::filesystem::path(scene).stem().c_str(), seeds, spp,
                double(values / 3) * variance / (sigma * sigma));
}
