// Speed against error: renders a scene progressively along a ladder of samples per pixel and
// records, at each rung, the wall time so far, the RMSE against a converged reference and the
// renderer's own error estimate. One CSV row per rung, for bench/plot_speed_vs_error.py.
//
// Modes switch the techniques one at a time, so each one's gain shows:
//   glint        the scene as written (auto: BVH, light sampling with MIS, light tracing of
//                caustics where the scene has them)
//   no-lt        glint without light tracing
//   no-nee       BVH, no light sampling, no light tracing
//   no-bvh       light sampling and light tracing, every primitive tested
//   smallpt      none: smallpt's estimator (independent random samples) and its brute-force
//                intersection
#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include <chrono>
#include <cstdio>
#include <filesystem>

#include "assembly/scene_loader.h"
#include "base/files.h"
#include "io/image_io.h"
#include "render/renderer.h"
#include "reference_image.h"

using namespace glint;
namespace fs = std::filesystem;

namespace {

struct Options {
    std::string scene, out, modes = "glint,no-lt,no-nee,no-bvh,smallpt";
    int width = 256, height = 192;
    unsigned threads = 2;
    uint32_t reference_spp = 4096, max_spp = 1024;
    double max_seconds = 120;
};

LoadedScene load_mode(const Options& o, const std::string& mode) {
    nlohmann::json scene = nlohmann::json::parse(read_file(o.scene, size_t(64) << 20));
    if (!scene.contains("integrator")) scene["integrator"] = nlohmann::json::object();
    nlohmann::json& integrator = scene["integrator"];
    if (mode == "no-nee" || mode == "smallpt") integrator["light_sampling"] = false;
    if (mode == "no-lt" || mode == "no-nee" || mode == "smallpt") integrator["light_tracing"] = "off";
    if (mode == "no-bvh" || mode == "smallpt") integrator["accelerator"] = "list";
    if (mode == "smallpt") scene["film"]["sampler"] = "independent";
    if (mode == "smallpt") integrator["direct_view_rays"] = 0;
    LoadedScene loaded = parse_scene(scene.dump(), fs::path(o.scene).parent_path());
    loaded.settings.width = o.width;
    loaded.settings.height = o.height;
    return loaded;
}

void ladder(const Options& o, const std::string& mode, const Image& ref) {
    LoadedScene loaded = load_mode(o, mode);
    loaded.settings.spp = o.max_spp;
    ThreadPool pool(o.threads);
    RenderJob job(loaded.scene, loaded.settings);
    const uint32_t round = samples_per_round(loaded.settings.filter);
    const auto start = std::chrono::steady_clock::now();
    for (uint32_t done = 0, next = round; next <= o.max_spp; done = next, next *= 2) {
        job.render_pass(pool, done, next);
        const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
        const Image image = job.film().mean();
        std::printf("%s,%s,%u,%.4f,%.6g,%.6g\n", fs::path(o.scene).stem().c_str(), mode.c_str(), next, seconds,
                    rmse(image, ref), job.film().error_estimate());
        std::fflush(stdout);
        if (seconds > o.max_seconds) break;
    }
}

}  // namespace

int main(int argc, char** argv) {
    Options o;
    CLI::App app{"Speed against error along an SPP ladder (CSV on stdout)"};
    app.add_option("scene", o.scene, "Scene JSON")->required();
    app.add_option("--out", o.out, "Folder for the reference image")->required();
    app.add_option("--modes", o.modes, "Comma-separated: glint, no-lt, no-nee, no-bvh, smallpt");
    app.add_option("--width", o.width);
    app.add_option("--height", o.height);
    app.add_option("--threads", o.threads);
    app.add_option("--reference-spp", o.reference_spp);
    app.add_option("--max-spp", o.max_spp, "Top of the ladder (doubling from one round)");
    app.add_option("--max-seconds", o.max_seconds, "Stop a mode's ladder once it has run this long");
    CLI11_PARSE(app, argc, argv);
    fs::create_directories(o.out);
    const Image ref = reference_image(load_mode(o, "glint"), o.out, o.reference_spp, o.threads);
    std::stringstream modes(o.modes);
    for (std::string mode; std::getline(modes, mode, ',');) ladder(o, mode, ref);
}
