// The denoised preview against the unbiased image: renders a scene progressively along a ladder
// of samples per pixel and, at each rung, denoises the film and measures both images against a
// converged reference: RMSE, and relMSE (the mean over pixels and channels of
// (x - ref)² / (ref² + 0.01)). The denoiser's time is its CPU time (user + sys of the process
// while it runs: the machine is shared) and its wall time. One CSV row per rung, for
// bench/plot_denoise.py (columns: scene, width, height, spp, render CPU s so far, RMSE and relMSE
// of the unbiased image, of the denoised one, the denoiser's CPU s and wall s); the images of
// one rung are written as PNGs to look at, and as PFMs, with the reference as reference.png.
#include <CLI/CLI.hpp>
#include <sys/resource.h>

#include <chrono>
#include <cstdio>
#include <filesystem>

#include "base/files.h"
#include "denoise/denoiser.h"
#include "io/image_io.h"
#include "io/scene_loader.h"
#include "reference_image.h"
#include "render/renderer.h"

using namespace glint;
namespace fs = std::filesystem;

namespace {

struct Options {
    std::string scene, out;
    int width = 256, height = 192;
    unsigned threads = 2;
    uint32_t reference_spp = 4096, max_spp = 1024, png_spp = 16;
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

// One rung: the film as it is, denoised, both measured; PNGs of both at png_spp. `render_cpu`:
// the CPU seconds the render has taken so far.
void measure(const Options& o, const RenderJob& job, uint32_t spp, double render_cpu, const Image& ref,
             ThreadPool& pool) {
    const double cpu0 = cpu_seconds();
    const auto wall0 = std::chrono::steady_clock::now();
    const Image denoised = denoise(job.film(), o.config, pool);
    const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - wall0).count();
    const double cpu = cpu_seconds() - cpu0;
    const Image image = job.film().mean();
    const std::string name = fs::path(o.scene).stem().string();
    std::printf("%s,%d,%d,%u,%.4f,%.6g,%.6g,%.6g,%.6g,%.4f,%.4f\n", name.c_str(), o.width, o.height, spp, render_cpu,
                rmse(image, ref), rel_mse(image, ref), rmse(denoised, ref), rel_mse(denoised, ref), cpu, wall);
    std::fflush(stdout);
    if (spp != o.png_spp) return;
    const std::string stem = (fs::path(o.out) / (name + "-" + std::to_string(spp) + "spp")).string();
    write_file(stem + ".png", encode_png(image, job.settings().encoding));
    write_file(stem + ".denoised.png", encode_png(denoised, job.settings().encoding));
    write_file(stem + ".pfm", encode_pfm(image));
    write_file(stem + ".denoised.pfm", encode_pfm(denoised));
    write_file((fs::path(o.out) / "reference.png").string(), encode_png(ref, job.settings().encoding));
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
    app.add_option("--png-spp", o.png_spp, "The rung whose images are written as PNGs");
    app.add_option("--window-radius", o.config.window_radius);
    app.add_option("--patch-radius", o.config.patch_radius);
    app.add_option("--variance-cancel", o.config.variance_cancel);
    app.add_option("--selection-radius", o.config.selection_radius);
    app.add_flag("--colour-only", o.colour_only, "Render without AOVs: the denoiser compares colours only");
    CLI11_PARSE(app, argc, argv);
    fs::create_directories(o.out);
    LoadedScene loaded = load_scene(o.scene);
    loaded.settings.width = o.width;
    loaded.settings.height = o.height;
    const Image ref = reference_image(loaded, o.out, o.reference_spp, o.threads);
    loaded.settings.spp = o.max_spp;
    loaded.settings.aovs = !o.colour_only;
    ThreadPool pool(o.threads);
    RenderJob job(loaded.scene, loaded.settings);
    const uint32_t round = samples_per_round(loaded.settings.filter);
    double render_cpu = 0;
    for (uint32_t done = 0, next = round; next <= o.max_spp; done = next, next *= 2) {
        const double start = cpu_seconds();
        job.render_pass(pool, done, next);
        render_cpu += cpu_seconds() - start;
        measure(o, job, next, render_cpu, ref, pool);
    }
}
