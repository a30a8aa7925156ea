// The denoised preview against the unbiased image: renders a scene progressively along a ladder
// of samples per pixel and, at each rung, denoises the film and measures both images against a
// converged reference: RMSE, and relMSE (the mean over pixels and channels of
// (x - ref)² / (ref² + 0.01)). The denoiser's time is its CPU time (user + sys of the process
// while it runs: the machine is shared) and its wall time. One CSV row per rung, for
// bench/plot_denoise.py (columns: scene, width, height, spp, render CPU s so far, RMSE and relMSE
// of the unbiased image, of the denoised one, the denoiser's CPU s and wall s); the images of
// one rung are written as PNGs to look at, and as PFMs, with the reference as reference.png.
// With --seeds N the ladder is rendered N times, each with its own seed, and every figure is the
// mean over them (RMSE the root of the mean squared error): one 16 spp image of a scene with
// fireflies can be off its expected relMSE by 1.5×.
#include <CLI/CLI.hpp>
#include <sys/resource.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>

#include "assembly/scene_loader.h"
#include "base/files.h"
#include "denoise/denoiser.h"
#include "denoise/denoiser_config.h"
#include "io/image_io.h"
#include "reference_image.h"
#include "render/renderer.h"

using namespace glint;
namespace fs = std::filesystem;

namespace {

struct Options {
    std::string scene, out;
    int width = 256, height = 192;
    unsigned threads = 2;
    uint32_t reference_spp = 4096, max_spp = 1024, png_spp = 16, seeds = 1;
    DenoiserConfig config;  // the defaults unless options change them
    bool colour_only = false;
};

double cpu_seconds() {
    rusage usage{};
    getrusage(RUSAGE_SELF, &usage);
    const auto seconds = [](const timeval& t) { return double(t.tv_sec) + double(t.tv_usec) * 1e-6; };
    return seconds(usage.ru_utime) + seconds(usage.ru_stime);
}

double rel_mse(const Image& image, const Image& ref) {
    double total = 0;
    for (size_t i = 0; i < ref.rgb.size(); ++i) {
        const double d = double(image.rgb[i]) - ref.rgb[i];
        total += d * d / (double(ref.rgb[i]) * ref.rgb[i] + 0.01);
    }
    return total / double(ref.rgb.size());
}

// One rung's figures, summed over the seeds: squared errors, times.
struct Rung {
    double render_cpu = 0, mse = 0, relmse = 0, mse_denoised = 0, relmse_denoised = 0, denoise_cpu = 0, denoise_wall = 0;
};

// One rung of one seed: the film as it is, denoised, both measured and added to `rung`; PNGs and
// PFMs of both at png_spp for the first seed. `render_cpu`: the CPU seconds the render has taken
// so far.
void measure(const Options& o, const RenderJob& job, uint32_t spp, bool first_seed, const Image& ref,
             ThreadPool& pool, Rung& rung) {
    const double cpu0 = cpu_seconds();
    const auto wall0 = std::chrono::steady_clock::now();
    const Image denoised = denoise_with(half_buffers(job.film()), o.config, pool);
    rung.denoise_wall += std::chrono::duration<double>(std::chrono::steady_clock::now() - wall0).count();
    rung.denoise_cpu += cpu_seconds() - cpu0;
    const Image image = job.film().mean();
    const double error = rmse(image, ref), error_denoised = rmse(denoised, ref);
    rung.mse += error * error;
    rung.relmse += rel_mse(image, ref);
    rung.mse_denoised += error_denoised * error_denoised;
    rung.relmse_denoised += rel_mse(denoised, ref);
    if (spp != o.png_spp || !first_seed) return;
    const std::string name = fs::path(o.scene).stem().string();
    const std::string stem = (fs::path(o.out) / (name + "-" + std::to_string(spp) + "spp")).string();
    write_file(stem + ".png", encode_png(image, job.settings().encoding));
    write_file(stem + ".denoised.png", encode_png(denoised, job.settings().encoding));
    write_file(stem + ".pfm", encode_pfm(image));
    write_file(stem + ".denoised.pfm", encode_pfm(denoised));
    write_file((fs::path(o.out) / "reference.png").string(), encode_png(ref, job.settings().encoding));
}

// The ladder of one seed, its figures added to `rungs` (one per rung, doubling from one round).
void render_ladder(const Options& o, LoadedScene loaded, uint32_t seed_index, const Image& ref, ThreadPool& pool,
                   std::vector<Rung>& rungs) {
    loaded.settings.spp = o.max_spp;
    loaded.settings.aovs = !o.colour_only;
    loaded.settings.seed += seed_index;
    RenderJob job(loaded.scene, loaded.settings);
    const uint32_t round = samples_per_round(loaded.settings.filter);
    double render_cpu = 0;
    size_t r = 0;
    for (uint32_t done = 0, next = round; next <= o.max_spp; done = next, next *= 2, ++r) {
        const double start = cpu_seconds();
        job.render_pass(pool, done, next);
        render_cpu += cpu_seconds() - start;
        if (rungs.size() <= r) rungs.emplace_back();
        rungs[r].render_cpu += render_cpu;
        measure(o, job, next, seed_index == 0, ref, pool, rungs[r]);
    }
}

}  // namespace

int main(int argc, char** argv) {
    Options o;
    CLI::App app{"The denoised preview's error and time along an SPP ladder (CSV on stdout)"};
    app.add_option("scene", o.scene, "Scene JSON")->required();
    app.add_option("--out", o.out, "Folder for the reference image and the PNGs")->required();
    app.add_option("--width", o.width);
    app.add_option("--height", o.height);
    app.add_option("--threads", o.threads);
    app.add_option("--reference-spp", o.reference_spp);
    app.add_option("--max-spp", o.max_spp, "Top of the ladder (doubling from one round)");
    app.add_option("--png-spp", o.png_spp, "The rung whose images are written as PNGs (of the first seed)");
    app.add_option("--seeds", o.seeds, "Renders of the ladder, each with its own seed: the figures are their means")
        ->check(CLI::Range(1, 64));
    app.add_option("--window-radius", o.config.filters[0].window_radius, "The wide filter's");
    app.add_option("--patch-radius", o.config.filters[0].patch_radius, "The wide filter's");
    bool wide_only = false;
    app.add_flag("--wide-only", wide_only, "Leave the local filter out (the denoiser before it had one)");
    app.add_option("--variance-cancel", o.config.variance_cancel);
    app.add_option("--selection-radius", o.config.selection_radius);
    app.add_option("--relative-error-floor", o.config.relative_error_floor);
    app.add_flag("--colour-only", o.colour_only, "Render without AOVs: the denoiser compares colours only");
    CLI11_PARSE(app, argc, argv);
    if (wide_only) o.config.filters.resize(1);
    fs::create_directories(o.out);
    LoadedScene loaded = load_scene(o.scene);
    loaded.settings.width = o.width;
    loaded.settings.height = o.height;
    const Image ref = reference_image(loaded, o.out, o.reference_spp, o.threads);
    ThreadPool pool(o.threads);
    std::vector<Rung> rungs;
    for (uint32_t seed = 0; seed < o.seeds; ++seed) render_ladder(o, loaded, seed, ref, pool, rungs);
    // RMSE: the root of the seeds' mean squared error; relMSE and times: their means.
    const std::string name = fs::path(o.scene).stem().string();
    const double n = o.seeds;
    uint32_t spp = samples_per_round(loaded.settings.filter);
    for (const Rung& r : rungs) {
        std::printf("%s,%d,%d,%u,%.4f,%.6g,%.6g,%.6g,%.6g,%.4f,%.4f\n", name.c_str(), o.width, o.height, spp,
                    r.render_cpu / n, std::sqrt(r.mse / n), r.relmse / n, std::sqrt(r.mse_denoised / n),
                    r.relmse_denoised / n, r.denoise_cpu / n, r.denoise_wall / n);
        spp *= 2;
    }
}
