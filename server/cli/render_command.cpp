// `glint render`: scene files to PNG (and optionally PFM and EXR), or one scene's sample range to a
// partial file, with progress on the terminal. Ctrl-C stops the render and still writes the
// image rendered so far.
#include <csignal>
#include <cstdio>
#include <filesystem>
#include <optional>
#include <sstream>

#include <spdlog/spdlog.h>

#include "assembly/film_exr.h"
#include "assembly/film_overrides.h"
#include "assembly/fingerprint.h"
#include "assembly/partial_file.h"
#include "assembly/scene_loader.h"
#include "base/files.h"
#include "cli/commands.h"
#include "cli/option_range.h"
#include "cli/progress_bar.h"
#include "denoise/denoiser.h"
#include "service/checkpointer.h"

namespace glint {
namespace {

struct RenderOptions {
    std::vector<std::string> scenes;
    std::string output, hdr, exr, samples, partial, checkpoint, meshes;
    bool aovs = false;
    double checkpoint_interval = 5;
    std::optional<uint32_t> spp;
    std::optional<int> width, height;
    std::optional<uint64_t> seed;
    std::optional<std::string> encoding;
    unsigned threads = 0;
    std::optional<double> target_error, time_limit, adaptive_threshold;
    std::optional<uint32_t> adaptive_min_spp;
    std::vector<int> region;  // x0, y0, x1, y1, when given
    bool denoise = false;
};

// Where one scene's results go.
struct Outputs {
    std::string png, hdr, exr, partial, checkpoint;
    std::string denoised;  // OUT.denoised.png beside the PNG, with --denoise
};

// "out.png" -> "out.denoised.png": the denoised preview beside the unbiased image.
std::string denoised_path(const std::string& png, bool denoise) {
    return denoise ? std::filesystem::path(png).replace_extension(".denoised.png").string() : "";
}

RenderJob* g_interruptible = nullptr;

void on_interrupt(int) {
    if (g_interruptible) g_interruptible->cancel();  // an atomic store: async-signal-safe
}

// "A:B" -> samples [A, B).
void apply_sample_range(const std::string& range, FilmOverrides& o) {
    unsigned first = 0, end = 0;
    char colon = 0;
    std::istringstream in(range);
    if (!(in >> first >> colon >> end) || colon != ':' || !in.eof() || end <= first)
        throw SceneError("--samples", "must be A:B with A < B (got \"" + range + "\")");
    o.first_sample = first;
    o.spp = end - first;
}

// The film options given, over the scene's; check_settings() then bounds the result as it bounds
// a scene file's and a job request's.
FilmOverrides film_overrides(const RenderOptions& o) {
    FilmOverrides f;
    f.spp = o.spp;
    f.job_spp = o.spp;  // --samples replaces f.spp with the part's
    f.width = o.width;
    f.height = o.height;
    f.seed = o.seed;
    if (o.encoding) f.encoding = encoding_named(*o.encoding);
    if (!o.samples.empty()) apply_sample_range(o.samples, f);
    f.target_error = o.target_error;
    f.time_limit = o.time_limit;
    f.adaptive_threshold = o.adaptive_threshold;
    f.adaptive_min_spp = o.adaptive_min_spp;
    if (!o.region.empty()) f.region = Region{o.region[0], o.region[1], o.region[2], o.region[3]};
    if (o.aovs || !o.exr.empty()) f.aovs = true;
    return f;
}

// `print` is the fingerprint of the scene and settings (needed only for a partial file).
void write_outputs(const RenderJob& job, uint64_t print, const Outputs& out, ThreadPool& pool) {
    const Image image = job.film().mean();
    if (!out.png.empty()) write_file(out.png, encode_png(image, job.settings().encoding));
    std::vector<ExrLayer> extra;
    if (!out.denoised.empty()) {
        const Image denoised = denoise(job.film(), pool);
        write_file(out.denoised, encode_png(denoised, job.settings().encoding));
        extra.push_back(exr_layer("denoised", denoised));
    }
    if (!out.hdr.empty()) write_file(out.hdr, encode_pfm(image));
    if (!out.exr.empty()) write_file(out.exr, encode_film_exr(image, job.film(), std::move(extra)));
    if (!out.partial.empty()) write_file(out.partial, encode_partial(partial_of(job, print, job.progress().spp_done)));
}

// --checkpoint FILE: the film of the whole passes done, kept in FILE (a partial file) at pass ends
// at most every `interval` seconds; a render that finds the file continues from it, with the
// samples and sums an uninterrupted render would have (a killed or requeued part of a split job
// loses only what it rendered since). Removed once a render that reached its sample count has
// written its outputs; a render stopped short keeps the last one, taken at a pass end.
class Checkpoint {
public:
    Checkpoint(std::string path, double interval, uint64_t fingerprint)
        : path_(std::move(path)), checkpointer_(interval, fingerprint) {}

    // Continues `job` from the file if there is one; throws SceneError if it cannot.
    void resume(RenderJob& job) const {
        if (path_.empty() || !std::filesystem::exists(path_)) return;
        try {
            const Partial saved = decode_partial(read_file(path_, size_t(8) << 30));
            checkpointer_.resume(job, saved);
            spdlog::info("{}: continuing from sample {}", path_, saved.end_sample);
        } catch (const std::exception& e) {
            throw SceneError("--checkpoint", path_ + " cannot be continued: " + e.what() + " (remove it to start over)");
        }
    }
    void after_pass(const RenderJob& job) {
        if (path_.empty()) return;
        checkpointer_.after_pass(job, [&](const Partial& film) { write_file(path_, encode_partial(film)); });
    }
    void remove() const {
        if (!path_.empty()) std::filesystem::remove(path_);
    }

private:
    std::string path_;
    Checkpointer checkpointer_;
};

// Renders one scene; returns the exit status (0 done, 1 failed, 130 interrupted).
int render_scene(const RenderOptions& o, const std::string& scene, const Outputs& out, ThreadPool& pool) {
    LoadedScene loaded;
    try {
        loaded = load_scene(scene, {}, o.meshes);
        apply_film_overrides(film_overrides(o), loaded.settings, SceneLimits{});
        loaded.settings.aovs |= o.denoise;  // the denoiser's features
    } catch (const SceneError& e) {
        std::fprintf(stderr, "glint: %s: %s\n", scene.c_str(), e.what());
        return 1;
    }
    for (const std::string& w : loaded.warnings) spdlog::warn("{}: {}", scene, w);
    const Geometry& g = loaded.scene->geometry();
    spdlog::info("{}: {} spheres, {} triangles ({} degenerate, ignored), {} lights; {}x{}, {} spp", scene,
                 g.sphere_count(), g.triangle_count(), g.degenerate_triangles(), loaded.scene->lights().size(),
                 loaded.settings.width, loaded.settings.height, loaded.settings.spp);
    RenderJob job(loaded.scene, loaded.settings);
    // Hashing the scene costs a pass over every triangle: only for the files that carry it.
    const uint64_t print =
        out.partial.empty() && out.checkpoint.empty() ? 0 : fingerprint(*loaded.scene, loaded.settings);
    Checkpoint checkpoint(out.checkpoint, o.checkpoint_interval, print);
    try {
        checkpoint.resume(job);
    } catch (const SceneError& e) {
        std::fprintf(stderr, "glint: %s: %s\n", scene.c_str(), e.what());
        return 1;
    }
    ProgressBar bar(stderr);
    g_interruptible = &job;
    const StopReason reason = job.run(pool, [&](const Progress& p) {
        bar.update(p);
        checkpoint.after_pass(job);
    });
    bar.finish();
    g_interruptible = nullptr;
    try {
        write_outputs(job, print, out, pool);
        if (reason == StopReason::completed) checkpoint.remove();
    } catch (const std::exception& e) {
        std::fprintf(stderr, "glint: %s\n", e.what());
        return 1;
    }
    const Progress p = job.progress();
    std::printf("%s: %s; %u spp at %dx%d in %.2f s, %.3g samples/s, estimated RMSE %.4g, "
                "%llu samples dropped (rounds with a non-finite one)\n",
                (!out.png.empty() ? out.png : !out.exr.empty() ? out.exr : out.partial).c_str(), to_string(reason), p.spp_done, job.settings().width,
                job.settings().height, p.seconds, p.samples_per_second, p.error_estimate,
                static_cast<unsigned long long>(p.dropped));
    return reason == StopReason::cancelled ? 130 : 0;
}

// Several scene files, or folders of them, rendered one after another into the output folder;
// a scene that fails does not stop the others.
int render_batch(const RenderOptions& o, ThreadPool& pool) {
    std::vector<std::filesystem::path> scenes;
    for (const auto& arg : o.scenes) {
        if (!std::filesystem::is_directory(arg)) {
            scenes.emplace_back(arg);
            continue;
        }
        std::vector<std::filesystem::path> found;
        for (const auto& entry : std::filesystem::directory_iterator(arg))
            if (entry.path().extension() == ".json") found.push_back(entry.path());
        std::sort(found.begin(), found.end());
        scenes.insert(scenes.end(), found.begin(), found.end());
    }
    for (const std::string& folder : {o.output, o.hdr, o.exr})
        if (!folder.empty()) std::filesystem::create_directories(folder);
    const auto in = [&](const std::string& folder, const std::string& file) {
        return folder.empty() ? "" : (std::filesystem::path(folder) / file).string();
    };
    int failed = 0;
    for (const auto& scene : scenes) {
        const std::string stem = scene.stem().string();
        const std::string png = in(o.output, stem + ".png");
        Outputs out{png, in(o.hdr, stem + ".pfm"), in(o.exr, stem + ".exr"), "", "", denoised_path(png, o.denoise)};
        const int status = render_scene(o, scene.string(), out, pool);
        if (status == 130) return 130;
        failed += status != 0;
    }
    std::printf("%zu scenes: %zu rendered, %d failed\n", scenes.size(), scenes.size() - size_t(failed), failed);
    return failed ? 1 : 0;
}

int run_render(const RenderOptions& o) {
    struct sigaction action {};
    action.sa_handler = on_interrupt;
    action.sa_flags = SA_RESETHAND;  // a second Ctrl-C ends the process at once
    sigaction(SIGINT, &action, nullptr);
    ThreadPool pool(o.threads);
    const bool batch = o.scenes.size() > 1 || std::filesystem::is_directory(o.scenes.front());
    if (batch && (!o.samples.empty() || !o.partial.empty() || !o.checkpoint.empty())) {
        std::fprintf(stderr, "glint: --samples, --partial and --checkpoint take a single scene file\n");
        return 2;
    }
    if (o.output.empty() && o.exr.empty() && o.partial.empty()) {
        std::fprintf(stderr, "glint: give -o (a PNG, or a folder for several scenes), --exr or --partial\n");
        return 2;
    }
    if (o.denoise && o.output.empty()) {
        std::fprintf(stderr, "glint: --denoise writes OUT.denoised.png beside the PNG: give -o\n");
        return 2;
    }
    if (batch) return render_batch(o, pool);
    return render_scene(o, o.scenes.front(),
                        Outputs{o.output, o.hdr, o.exr, o.partial, o.checkpoint, denoised_path(o.output, o.denoise)},
                        pool);
}

}  // namespace

std::function<int()> add_render_command(CLI::App& app) {
    auto o = std::make_shared<RenderOptions>();
    CLI::App* cmd = app.add_subcommand("render", "Render scene files to PNG images");
    cmd->add_option("scenes", o->scenes, "Scene JSON files, or folders of them")->required();
    cmd->add_option("-o,--output", o->output, "PNG file to write (a folder when rendering several scenes)");
    cmd->add_option("--hdr", o->hdr, "Also write the linear image as PFM (a folder for several scenes)");
    cmd->add_option("--exr", o->exr,
                    "Also write an OpenEXR file: the linear image, sample counts, variance and AOVs (a folder for "
                    "several scenes; turns on --aovs)");
    cmd->add_flag("--aovs", o->aovs, "Keep the AOVs (albedo, normal, depth) in the film and its partial files (film.aovs)");
    cmd->add_option("--samples", o->samples, "Render only samples A..B-1 of every pixel (A:B), for --partial");
    cmd->add_option("--partial", o->partial, "Write the per-pixel sums to this file, for glint merge");
    cmd->add_flag("--denoise", o->denoise,
                  "Also write OUT.denoised.png, a denoised preview (docs/denoiser.md); OUT stays the unbiased image");
    cmd->add_option("--scenes", o->meshes, "Folder the scene's mesh files are read from (default: the scene file's)");
    cmd->add_option("--checkpoint", o->checkpoint,
                    "Keep the film in this file as the render goes, and continue from it if it is there");
    in_range(cmd->add_option("--checkpoint-interval", o->checkpoint_interval,
                             "Seconds between checkpoints (default 5; 0: after every pass)"),
             checkpoint_seconds());
    in_range(cmd->add_option("--spp", o->spp, "Samples per pixel (film.spp)"), film_option(FilmInteger::spp));
    in_range(cmd->add_option("--width", o->width, "Image width (film.width)"), film_option(FilmInteger::width));
    in_range(cmd->add_option("--height", o->height, "Image height (film.height)"), film_option(FilmInteger::height));
    in_range(cmd->add_option("--threads", o->threads, "Render threads (default 0: all cores)"), thread_count());
    in_range(cmd->add_option("--seed", o->seed, "Random seed (film.seed)"), film_option(FilmInteger::seed));
    cmd->add_option("--encoding", o->encoding, "PNG encoding (film.encoding)")->check(CLI::IsMember({"gamma2.2", "srgb"}));
    // Checked by check_settings(), with the scene file's and a job request's values.
    cmd->add_option("--target-error", o->target_error,
                    "Stop once the estimated RMSE is at most this (film.target_error; >= 0, 0: off)");
    cmd->add_option("--time-limit", o->time_limit, "Stop after this many seconds (film.time_limit; >= 0, 0: off)");
    in_range(cmd->add_option("--adaptive-threshold", o->adaptive_threshold,
                             "Stop sampling pixels whose relative error is below this (film.adaptive.threshold; 0: off)"),
             numbers(0, kMaxAdaptiveThreshold));
    const IntegerRange min_spp = adaptive_min_spp_range(SceneLimits{});
    in_range(cmd->add_option("--adaptive-min-spp", o->adaptive_min_spp,
                             "Samples before a pixel may stop (film.adaptive.min_spp; 0: automatic)"),
             integers(min_spp.min, min_spp.max));
    cmd->add_option("--region", o->region,
                    "Render only the window X0,Y0,X1,Y1 (pixels, rows from the top, X1 and Y1 excluded; film.region)")
        ->delimiter(',')
        ->expected(4);
    return [o] { return run_reporting_errors([&] { return run_render(*o); }); };
}

}  // namespace glint
