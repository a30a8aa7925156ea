// `glint serve`: the render service until SIGINT or SIGTERM, then a graceful stop and exit 0.
#include <csignal>

#include <spdlog/spdlog.h>

#include "cli/commands.h"
#include "cli/option_range.h"
#include "http/render_server.h"

namespace glint {
namespace {

// `glint serve` has no settings of its own: its options fill the two layers' configurations.
struct ServeOptions {
    ServiceConfig service;
    HttpConfig http;
};

int run_serve(const ServeOptions& o) {
    // Block the stop signals in every thread (they inherit the mask); this one waits for them.
    sigset_t stop_signals;
    sigemptyset(&stop_signals);
    sigaddset(&stop_signals, SIGINT);
    sigaddset(&stop_signals, SIGTERM);
    pthread_sigmask(SIG_BLOCK, &stop_signals, nullptr);
    std::signal(SIGPIPE, SIG_IGN);  // a client that hangs up must not end the process
    try {
        RenderServer server(o.service, o.http);
        int signal = 0;
        sigwait(&stop_signals, &signal);
        spdlog::info("received {}", signal == SIGINT ? "SIGINT" : "SIGTERM");
        server.stop();
    } catch (const std::exception& e) {
        spdlog::error("{}", e.what());
        return 1;
    }
    return 0;
}

}  // namespace

std::function<int()> add_serve_command(CLI::App& app) {
    auto o = std::make_shared<ServeOptions>();
    CLI::App* cmd = app.add_subcommand("serve", "Run the HTTP render service");
    cmd->add_option("--host", o->http.host, "Address to listen on (default 127.0.0.1: this machine only)")
        ->envname("GLINT_HOST");
    in_range(cmd->add_option("--port", o->http.port, "Port (default 8080)"), integers(1, 65535));
    in_range(cmd->add_option("--threads", o->service.threads, "Render threads shared by all jobs (default 0: all cores)"),
             thread_count());
    cmd->add_option("--scenes", o->service.scenes, "Scene folder: presets and the only place meshes are read from");
    cmd->add_option("--web", o->http.web, "Folder of the web page");
    // Each running job holds a thread of its own and its film (128 bytes a pixel), each queued
    // one its scene: enough for any machine, and a typo cannot ask for 100000 threads.
    in_range(cmd->add_option("--max-jobs", o->service.max_running, "Jobs rendering at once (default 4)"),
             integers(1, 256));
    in_range(cmd->add_option("--max-queued", o->service.max_queued, "Jobs waiting before new ones get 429 (default 16)"),
             integers(1, 1024));
    // A denoised preview takes every core while it is made (service/denoise_gate.h).
    in_range(cmd->add_option("--max-denoising", o->service.max_denoising,
                             "Denoised previews made at once before requests for more get 429 (default 2)"),
             integers(1, 64));
    cmd->add_option("--store", o->service.store.dir, "Folder that keeps every job (scene, state, film) across restarts");
    in_range(cmd->add_option("--checkpoint-interval", o->service.store.checkpoint_interval,
                             "Seconds between checkpoints of a running job's film (default 5; 0: after every pass)"),
             checkpoint_seconds());
    in_range(cmd->add_option("--store-limit", o->service.store.limit_bytes,
                             "Bytes the store may hold; the oldest finished jobs are evicted beyond (default 2 GiB)"),
             integers(1, INT64_MAX));
    in_range(cmd->add_option("--asset-cache", o->service.asset_cache_bytes,
                             "Bytes of decoded textures and environments kept between jobs (default 1 GiB)"),
             integers(0, INT64_MAX));
    CLI::Option* farm_dir =
        cmd->add_option("--farm-dir", o->service.farm.dir, "Folder for the parts, on a filesystem every node sees");
    cmd->add_option_function<std::string>(
           "--farm", [o](const std::string&) { o->service.farm.slurm = true; },
           "Render every job on a Slurm cluster (the one value: slurm); needs --farm-dir")
        ->check(CLI::IsMember({"slurm"}))
        ->needs(farm_dir);
    in_range(cmd->add_option("--farm-parts", o->service.farm.parts, "Parts a job is split into (default 4)"),
             integers(1, 10000));
    cmd->add_option("--farm-glint", o->service.farm.glint, "Command that runs glint on a node (default: glint)");
    cmd->add_option("--farm-scripts", o->service.farm.scripts, "Folder of docker/slurm's scripts (default docker/slurm)");
    cmd->add_option("--farm-sbatch", o->service.farm.sbatch, "More sbatch options for every part, as one string");
    in_range(cmd->add_option("--farm-checkpoint-interval", o->service.farm.checkpoint_interval,
                             "Seconds between a part's checkpoints, which the server shows as they come (default 2)"),
             checkpoint_seconds());
    cmd->add_option("--token", o->http.token, "Bearer token the job routes require (needed off loopback)")->envname("GLINT_TOKEN");
    return [o] { return run_serve(*o); };
}

}  // namespace glint
