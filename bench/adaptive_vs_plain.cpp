// Adaptive sampling against plain sampling, in CPU time (user + sys of this process: the machine
// is shared, so wall time would measure the other work too). For one scene: a ladder of plain
// renders (spp doubling from 16) and adaptive renders at each threshold given (up to
// --adaptive-spp), each from scratch, alternating per repeat. The RMSE against the converged
// image is measured by pairs of renders with different seeds (as tests/support/test_support.h's
// measure_by_pairs): a reference would need many times the ladder's samples for its own noise
// to stay out of the figures. CSV on stdout for bench/plot_adaptive.py.
#include <CLI/CLI.hpp>
#include <sys/resource.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <sstream>

#include "io/scene_loader.h"
#include "render/renderer.h"

using namespace glint;
namespace fs = std::filesystem;

namespace {

struct Options {
    std::string scene, thresholds = "0.02";
    int width = 128, height = 96;
    unsigned threads = 2, repeats = 1;
    uint32_t max_spp = 256, adaptive_spp = 1024;
};

double cpu_seconds() {
    rusage u{};
    getrusage(RUSAGE_SELF, &u);
    return double(u.ru_utime.tv_sec + u.ru_stime.tv_sec) + 1e-6 * double(u.ru_utime.tv_usec + u.ru_stime.tv_usec);
}

LoadedScene load(const Options& o, uint32_t spp, double threshold, uint64_t seed) {
    LoadedScene loaded = load_scene(o.scene);
    loaded.settings.width = o.width;
    loaded.settings.height = o.height;
    loaded.settings.region = {};
    loaded.settings.spp = spp;
    loaded.settings.seed = seed;
    loaded.settings.adaptive = AdaptiveSettings{threshold, 0, 0};
    return loaded;
}

// The render's image, with the CPU time and camera samples per pixel it took.
struct Run {
    Image image{1, 1};
    double cpu = 0, mean_spp = 0;
};
Run render(const LoadedScene& loaded, ThreadPool& pool) {
    RenderJob job(loaded.scene, loaded.settings);
    const double start = cpu_seconds();
    job.run(pool);
    return {job.film().mean(), cpu_seconds() - start, job.progress().mean_spp};
}

// Two renders with seeds 2·repeat and 2·repeat + 1: independent and unbiased, so the mean square
// of their difference is twice either's MSE against the converged image. Reports one render's
// CPU time (the pair's mean) and samples.
void pair(const Options& o, const char* mode, double threshold, uint32_t spp, unsigned repeat, ThreadPool& pool) {
    const Run a = render(load(o, spp, threshold, 2 * repeat), pool);
    const Run b = render(load(o, spp, threshold, 2 * repeat + 1), pool);
    const double d = rmse(a.image, b.image);
    std::printf("%s,%s,%g,%u,%u,%.4f,%.6g,%.2f\n", fs::path(o.scene).stem().c_str(), mode, threshold, spp, repeat,
                (a.cpu + b.cpu) / 2, d / std::sqrt(2.0), (a.mean_spp + b.mean_spp) / 2);
    std::fflush(stdout);
}

}  // namespace

int main(int argc, char** argv) {
    Options o;
    CLI::App app{"Adaptive against plain sampling: CPU time and RMSE (CSV on stdout)"};
    app.add_option("scene", o.scene, "Scene JSON")->required();
    app.add_option("--width", o.width);
    app.add_option("--height", o.height);
    app.add_option("--threads", o.threads);
    app.add_option("--repeats", o.repeats);
    app.add_option("--max-spp", o.max_spp, "Top of the plain ladder (doubling from 16)");
    app.add_option("--adaptive-spp", o.adaptive_spp, "The adaptive renders' spp (their most per pixel)");
    app.add_option("--thresholds", o.thresholds, "Comma-separated adaptive thresholds");
    CLI11_PARSE(app, argc, argv);
    ThreadPool pool(o.threads);
    for (unsigned repeat = 1; repeat <= o.repeats; ++repeat) {
        for (uint32_t spp = 16; spp <= o.max_spp; spp *= 2) pair(o, "plain", 0, spp, repeat, pool);
        std::stringstream list(o.thresholds);
        for (std::string t; std::getline(list, t, ',');) pair(o, "adaptive", std::stod(t), o.adaptive_spp, repeat, pool);
    }
}
