// `glint render`: a scene file to PNG (and optionally PFM), with progress on the terminal.
// Ctrl-C stops the render and still writes the image rendered so far.
#include <csignal>
#include <cstdio>
#include <optional>

#include "commands.h"
#include "files.h"
#include "progress_bar.h"
#include "scene_loader.h"

#include <spdlog/spdlog.h>

namespace glint {
namespace {

struct RenderOptions {
    std::string scene, output, hdr;
    std::optional<uint32_t> spp;
    std::optional<int> width, height;
    std::optional<uint64_t> seed;
    std::optional<std::string> encoding;
    unsigned threads = 0;
    double target_error = 0, time_limit = 0;
};

RenderJob* g_interruptible = nullptr;

void on_interrupt(int) {
    if (g_interruptible) g_interruptible->cancel();  // an atomic store: async-signal-safe
}

void apply_overrides(const RenderOptions& o, RenderSettings& s) {
    if (o.spp) s.spp = *o.spp;
    if (o.width) s.width = *o.width;
    if (o.height) s.height = *o.height;
    if (o.seed) s.seed = *o.seed;
    if (o.encoding) s.encoding = *o.encoding == "srgb" ? Encoding::srgb : Encoding::gamma22;
    s.target_error = o.target_error;
    s.time_limit = o.time_limit;
}

int run_render(const RenderOptions& o) {
    LoadedScene loaded;
    try {
        loaded = load_scene(o.scene);
        apply_overrides(o, loaded.settings);
        check_settings(loaded.settings, SceneLimits{});
    } catch (const SceneError& e) {
        std::fprintf(stderr, "glint: %s: %s\n", o.scene.c_str(), e.what());
        return 1;
    }
    const Geometry& g = loaded.scene->geometry();
    spdlog::info("{}: {} spheres, {} triangles ({} degenerate, ignored), {} lights; {}x{}, {} spp", o.scene,
                 g.sphere_count(), g.triangle_count(), g.degenerate_triangles(), loaded.scene->lights().size(),
                 loaded.settings.width, loaded.settings.height, loaded.settings.spp);
    ThreadPool pool(o.threads);
    RenderJob job(loaded.scene, loaded.settings);
    ProgressBar bar(stderr);
    g_interruptible = &job;
    struct sigaction action {};
    action.sa_handler = on_interrupt;
    action.sa_flags = SA_RESETHAND;  // a second Ctrl-C ends the process at once
    sigaction(SIGINT, &action, nullptr);
    const StopReason reason = job.run(pool, [&](const Progress& p) { bar.update(p); });
    bar.finish();
    g_interruptible = nullptr;

    const Image image = job.film().mean();
    try {
        write_file(o.output, encode_png(image, job.settings().encoding));
        if (!o.hdr.empty()) write_file(o.hdr, encode_pfm(image));
    } catch (const std::exception& e) {
        std::fprintf(stderr, "glint: %s\n", e.what());
        return 1;
    }
    const Progress p = job.progress();
    std::printf("%s: %s; %u spp at %dx%d in %.2f s, %.3g samples/s, estimated RMSE %.4g, %llu non-finite samples dropped\n",
                o.output.c_str(), to_string(reason), p.spp_done, job.settings().width, job.settings().height, p.seconds,
                p.samples_per_second, p.error_estimate, static_cast<unsigned long long>(p.dropped));
    return reason == StopReason::cancelled ? 130 : 0;
}

}  // namespace

std::function<int()> add_render_command(CLI::App& app) {
    auto o = std::make_shared<RenderOptions>();
    CLI::App* cmd = app.add_subcommand("render", "Render a scene file to a PNG image");
    cmd->add_option("scene", o->scene, "Scene JSON file")->required();
    cmd->add_option("-o,--output", o->output, "PNG file to write")->required();
    cmd->add_option("--hdr", o->hdr, "Also write the linear image as PFM");
    cmd->add_option("--spp", o->spp, "Samples per pixel (film.spp)");
    cmd->add_option("--width", o->width, "Image width (film.width)");
    cmd->add_option("--height", o->height, "Image height (film.height)");
    cmd->add_option("--threads", o->threads, "Render threads (default: all cores)");
    cmd->add_option("--seed", o->seed, "Random seed (film.seed)");
    cmd->add_option("--encoding", o->encoding, "PNG encoding (film.encoding)")->check(CLI::IsMember({"gamma2.2", "srgb"}));
    cmd->add_option("--target-error", o->target_error, "Stop once the estimated RMSE is at most this")->check(CLI::NonNegativeNumber);
    cmd->add_option("--time-limit", o->time_limit, "Stop after this many seconds")->check(CLI::NonNegativeNumber);
    return [o] { return run_render(*o); };
}

}  // namespace glint
