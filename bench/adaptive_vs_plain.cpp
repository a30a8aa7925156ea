// Adaptive sampling against plain sampling, in CPU time (user + sys of this process: the machine
// is shared, so wall time would measure the other work too). For one scene: a ladder of plain
// renders (spp doubling from 16) and adaptive renders at each threshold given (up to
// --adaptive-spp), each from scratch, alternating per repeat, with their RMSE against a reference
// (two plain renders, its noise taken out) and, for comparison, by pairs of seeds (as
// tests/support/test_support.h's measure_by_pairs, which cannot see a bias adaptive stopping
// might have). CSV on stdout for bench/plot_adaptive.py.
#include <CLI/CLI.hpp>
#include <sys/resource.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <sstream>

#include "assembly/scene_loader.h"
#include "render/renderer.h"

using namespace glint;
namespace fs = std::filesystem;

namespace {

struct Options {
    std::string scene, thresholds = "0.02";
    int width = 128, height = 96;
    unsigned threads = 2, repeats = 1;
    uint32_t reference_spp = 1024, max_spp = 256, adaptive_spp = 1024;
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

// The converged image's stand-in: the mean of two plain renders of --reference-spp with seeds no
// other render uses, and its own MSE (a quarter of the mean square of their difference).
struct Reference {
    Image image{1, 1};
    double mse = 0;
};
Reference reference(const Options& o, ThreadPool& pool) {
    const Run a = render(load(o, o.reference_spp, 0, 1000), pool), b = render(load(o, o.reference_spp, 0, 1001), pool);
    Reference r{Image(a.image.width, a.image.height), 0};
    for (int y = 0; y < a.image.height; ++y)
        for (int x = 0; x < a.image.width; ++x) r.image.set(x, y, (a.image.at(x, y) + b.image.at(x, y)) / 2.0);
    const double d = rmse(a.image, b.image);
    r.mse = d * d / 4;
    return r;
}

// Two renders with seeds 2·repeat and 2·repeat + 1. `rmse`: against the reference, the
// reference's own MSE taken out (they are independent), so that a bias shows; `pairs`: from the
// two renders' difference alone (twice either's MSE), blind to a bias both share. Reports one
// render's CPU time (the pair's mean) and samples.
void pair(const Options& o, const char* mode, double threshold, uint32_t spp, unsigned repeat, ThreadPool& pool,
          const Reference& ref) {
    const Run a = render(load(o, spp, threshold, 2 * repeat), pool);
    const Run b = render(load(o, spp, threshold, 2 * repeat + 1), pool);
    const double ea = rmse(a.image, ref.image), eb = rmse(b.image, ref.image), d = rmse(a.image, b.image);
    const double mse = std::max(0.0, (ea * ea + eb * eb) / 2 - ref.mse);
    std::printf("%s,%s,%g,%u,%u,%.4f,%.6g,%.6g,%.2f\n", fs::path(o.scene).stem().c_str(), mode, threshold, spp, repeat,
                (a.cpu + b.cpu) / 2, std::sqrt(mse), d / std::sqrt(2.0), (a.mean_spp + b.mean_spp) / 2);
    std::fflush(stdout);
}

}  // namespace

int main(int argc, char** argv) {
    Options o;
    CLI::App app{"Adaptive against plain sampling: CPU time and RMSE (CSV on stdout)"};
    app.add_option("scene", o.scene, "Scene JSON")->required();
    app.add_option("--width", o.width, "Image width (default 128)");
    app.add_option("--height", o.height, "Image height (default 96)");
    app.add_option("--threads", o.threads, "Render threads (default 2)");
    app.add_option("--repeats", o.repeats, "Pairs of each render, alternating");
    app.add_option("--reference-spp", o.reference_spp, "Each of the reference's two renders");
    app.add_option("--max-spp", o.max_spp, "Top of the plain ladder (doubling from 16)");
    app.add_option("--adaptive-spp", o.adaptive_spp, "The adaptive renders' spp (their most per pixel)");
    app.add_option("--thresholds", o.thresholds, "Comma-separated adaptive thresholds");
    CLI11_PARSE(app, argc, argv);
    ThreadPool pool(o.threads);
    const Reference ref = reference(o, pool);
    for (unsigned repeat = 1; repeat <= o.repeats; ++repeat) {
        for (uint32_t spp = 16; spp <= o.max_spp; spp *= 2) pair(o, "plain", 0, spp, repeat, pool, ref);
        std::stringstream list(o.thresholds);
        for (std::string t; std::getline(list, t, ',');)
            pair(o, "adaptive", std::stod(t), o.adaptive_spp, repeat, pool, ref);
    }
}
