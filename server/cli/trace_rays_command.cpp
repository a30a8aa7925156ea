// `glint trace-rays`: closest hits (or any-hit) of a shared ray file against an OBJ mesh, with
// BVH build time and throughput, for comparing glint's BVH with others on identical rays.
#include <algorithm>
#include <chrono>
#include <cstdio>

#include "base/files.h"
#include "base/thread_pool.h"
#include "cli/commands.h"
#include "cli/option_range.h"
#include "io/obj_loader.h"
#include "io/ray_file.h"
#include "scene/geometry.h"

namespace glint {
namespace {

struct TraceOptions {
    std::string mesh, rays, output;
    unsigned threads = 1;
    int repeat = 3;
    bool any_hit = false;
};

void declare_options(CLI::App& cmd, TraceOptions& o) {
    cmd.add_option("mesh", o.mesh, "OBJ mesh")->required();
    cmd.add_option("rays", o.rays, "Ray file (RAYS0001)")->required();
    cmd.add_option("-o,--output", o.output, "Hit file to write (HITS0001)");
    in_range(cmd.add_option("--threads", o.threads, "Threads (default 1; 0: all cores)"), thread_count());
    in_range(cmd.add_option("--repeat", o.repeat, "Trace the set this many times and report the median (default 3)"),
             integers(1, 1000));
    cmd.add_flag("--any-hit", o.any_hit, "Occlusion queries instead of closest hits (t = 0 marks a hit)");
}

double seconds_since(std::chrono::steady_clock::time_point start) {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

void trace(const Geometry& geometry, const std::vector<RayRecord>& rays, bool any_hit, ThreadPool& pool,
           std::vector<HitRecord>& hits) {
    constexpr size_t kChunk = 4096;
    pool.parallel_for((rays.size() + kChunk - 1) / kChunk, [&](size_t chunk) {
        const size_t end = std::min(rays.size(), (chunk + 1) * kChunk);
        for (size_t i = chunk * kChunk; i < end; ++i) {
            const RayRecord& r = rays[i];
            const Ray ray{{r.o[0], r.o[1], r.o[2]}, {r.d[0], r.d[1], r.d[2]}, r.tmin, r.tmax};
            Hit hit;
            if (any_hit) {
                hits[i] = geometry.occluded(ray, kNoPrimitive) ? HitRecord{0, 0} : HitRecord{float(kInfinity), kNoPrimitive};
            } else if (geometry.intersect(ray, kNoPrimitive, hit)) {
                hits[i] = {float(hit.t), hit.prim};
            } else {
                hits[i] = {float(kInfinity), kNoPrimitive};
            }
        }
    });
}

int run_trace_rays(const TraceOptions& o) {
    const ObjMesh mesh = load_obj(o.mesh, size_t(1) << 30);
    const std::vector<RayRecord> rays = read_rays(o.rays);
    auto start = std::chrono::steady_clock::now();
    const Geometry geometry({}, to_triangles(mesh), Accelerator::bvh);
    const double build = seconds_since(start);
    ThreadPool pool(o.threads);
    std::vector<HitRecord> hits(rays.size());
    std::vector<double> times;
    for (int i = 0; i < o.repeat; ++i) {
        start = std::chrono::steady_clock::now();
        trace(geometry, rays, o.any_hit, pool, hits);
        times.push_back(seconds_since(start));
    }
    std::sort(times.begin(), times.end());
    const double median = times[times.size() / 2];
    const auto hit_count = std::count_if(hits.begin(), hits.end(),
                                         [](const HitRecord& h) { return h.prim != kNoPrimitive; });
    if (!o.output.empty()) write_hits(o.output, hits);
    const double triangles = double(mesh.triangles.size());
    std::printf(
        "triangles %zu  build %.1f ms  nodes %zu  %.1f BVH node bytes/triangle  %.1f with the triangles\n",
        mesh.triangles.size(), build * 1e3, geometry.triangle_bvh().nodes().size(),
        double(geometry.triangle_bvh().memory_bytes()) / triangles,
        double(geometry.memory_bytes()) / triangles);
    std::printf("rays %zu  %s  hits %td  threads %u  median of %d: %.3f s  %.2f Mrays/s\n", rays.size(),
                o.any_hit ? "any-hit" : "closest-hit", hit_count, pool.size(), o.repeat, median,
                double(rays.size()) / median / 1e6);
    return 0;
}

}  // namespace

std::function<int()> add_trace_rays_command(CLI::App& app) {
    return add_command<TraceOptions>(app, "trace-rays",
                                     "Trace a ray file against an OBJ mesh (BVH benchmark)",
                                     declare_options, run_trace_rays);
}

}  // namespace glint
