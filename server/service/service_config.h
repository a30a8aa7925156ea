// The render service's configuration: its render threads, how many jobs it runs, queues and
// keeps, what one job may ask for, and where jobs are kept across restarts. `glint serve` fills
// it from its options; the HTTP layer's own settings are in http/http_config.h.
#pragma once

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <string>

#include "assembly/asset_cache.h"
#include "assembly/scene_limits.h"

namespace glint {

// `glint serve --store DIR`: jobs on disk (service/job_store.h).
struct StoreConfig {
    // Empty: no store, jobs live in memory only and end with the process.
    std::filesystem::path dir;
    // Seconds between checkpoints of a running job: what a crash can lose, against the cost of
    // writing a whole film (128 bytes a pixel) that often.
    double checkpoint_interval = 5;
    // Bytes the store may hold; beyond, the oldest finished jobs are evicted, so a server that
    // runs for months does not fill its disk.
    uint64_t limit_bytes = uint64_t(2) << 30;
};

// `glint serve --farm slurm`: every job rendered on a Slurm cluster as a job array of sample
// ranges (service/slurm_farm.h) instead of on this server's threads.
struct FarmConfig {
    // False: jobs render here, and nothing below is used.
    bool slurm = false;
    // The parts' folder, one subfolder a job; every node must see it at the same path, and the
    // scenes folder too.
    std::filesystem::path dir;
    // Parts a job is split into: at most the nodes that should render it at once.
    unsigned parts = 4;
    // docker/slurm/: submit, render-part and merge.
    std::filesystem::path scripts = "docker/slurm";
    // The command that runs glint on a node (it may be several words: a container runner).
    std::string glint = "glint";
    // More sbatch options for every job (partition, account, CPUs per task), as one string.
    std::string sbatch;
    // Seconds between looks at the parts' progress: how soon a part's checkpoint shows.
    double poll_interval = 0.5;
    // Seconds between a part's checkpoints (glint render --checkpoint-interval).
    double checkpoint_interval = 2;
};

struct ServiceConfig {
    // Presets (GET /presets, {"preset": NAME}) and the only folder meshes are read from.
    std::filesystem::path scenes = "scenes";
    // Render threads shared by every job; 0: one per core.
    unsigned threads = 0;
    // Jobs rendering at once. They share the render threads round-robin, so a small job need
    // not wait for a large one to end; beyond this many, jobs queue.
    unsigned max_running = 4;
    // Jobs waiting for a slot; beyond, a submission is refused as busy (429), so a flood of
    // requests cannot hold unbounded memory in queued scenes.
    size_t max_queued = 16;
    // Denoised previews made at once (service/denoise_gate.h); beyond, a request for one is
    // refused as busy (429). Each takes every core while it is made.
    unsigned max_denoising = 2;
    // Finished jobs kept for their images; the oldest are forgotten beyond, bounding memory.
    size_t max_finished = 64;
    // What one job may ask for: tighter than the scene loader's defaults, since every client
    // shares this process's memory and a job keeps its film (128 bytes a pixel) in it.
    SceneLimits scene{
        .max_dimension = 4096, .max_pixels = int64_t(4096) * 4096, .max_spp = 1u << 16};
    // Bytes of decoded texture and environment files kept between jobs (assembly/asset_cache.h), so
    // that the jobs of one scene decode its images and build its environment's distribution once.
    size_t asset_cache_bytes = AssetCache::kDefaultBytes;
    StoreConfig store;
    FarmConfig farm;
};

}  // namespace glint
