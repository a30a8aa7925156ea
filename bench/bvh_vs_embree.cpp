// glint's BVH against Embree 3 (Debian's libembree-dev; linked here only, never in glint) on the
// identical shared ray sets: build times, Mrays/s for closest and any-hit queries at 1 and 2
// threads, bytes per triangle, and whether the answers agree (ties at shared edges accepted, as
// ../shared/rays/FORMAT.md §4 says). glint's binned tree faces Embree MEDIUM (binned SAH), its
// tree with spatial splits Embree HIGH (spatial splits). Prints markdown tables.
//   bvh_vs_embree SHARED_DIR [repeats]
#include <embree3/rtcore.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cstdio>
#include <functional>
#include <string>
#include <vector>

#include "embree_scene.h"
#include "spatial_splits.h"
#include "scene/geometry.h"
#include "io/obj_loader.h"
#include "io/ray_file.h"
#include "base/thread_pool.h"

using namespace glint;

namespace {

using Clock = std::chrono::steady_clock;
int g_repeats = 3;

double seconds(const std::function<void()>& f) {
    const auto start = Clock::now();
    f();
    return std::chrono::duration<double>(Clock::now() - start).count();
}

double median(std::vector<double> v) {
    std::sort(v.begin(), v.end());
    return v[v.size() / 2];
}

// Each of `runs` (each returns the seconds it measured) once a round, g_repeats rounds:
// times[run][round]. Interleaved rather than one block per engine, so that a burst of load on
// this shared machine falls on every engine alike instead of on whichever ran during it.
using Times = std::vector<std::vector<double>>;
Times interleaved_times(const std::vector<std::function<double()>>& runs) {
    Times times(runs.size());
    for (int round = 0; round < g_repeats; ++round)
        for (size_t i = 0; i < runs.size(); ++i) times[i].push_back(runs[i]());
    return times;
}

// The median over the rounds of a[round] / b[round]: a ratio of two runs taken in the same round
// is paired, so it holds steady where the machine's drift between rounds moves both runs' times
// alike.
double paired_ratio(const std::vector<double>& a, const std::vector<double>& b) {
    std::vector<double> ratios;
    for (size_t round = 0; round < a.size(); ++round) ratios.push_back(a[round] / b[round]);
    return median(std::move(ratios));
}

// Runs f(i) for every ray, in chunks, on `threads` threads.
void for_rays(ThreadPool& pool, size_t n, const std::function<void(size_t)>& f) {
    constexpr size_t kChunk = 4096;
    pool.parallel_for((n + kChunk - 1) / kChunk, [&](size_t c) {
        for (size_t i = c * kChunk, end = std::min(n, (c + 1) * kChunk); i < end; ++i) f(i);
    });
}

struct Embree {
    RTCDevice device = nullptr;
    RTCScene scene = nullptr;
    std::atomic<int64_t> bytes{0};

    Embree(const ObjMesh& mesh, RTCBuildQuality quality, double& build_seconds) {
        device = rtcNewDevice("threads=1");  // the build is timed single-threaded, like glint's
        rtcSetDeviceMemoryMonitorFunction(
            device, [](void* self, ssize_t n, bool) { static_cast<Embree*>(self)->bytes += n; return true; }, this);
        scene = new_embree_scene(device, mesh, quality);
        build_seconds = seconds([&] { rtcCommitScene(scene); });
    }
    ~Embree() {
        rtcReleaseScene(scene);
        rtcReleaseDevice(device);
    }

    HitRecord closest(const RayRecord& r) const {
        RTCIntersectContext context;
        rtcInitIntersectContext(&context);
        RTCRayHit rh{};
        rh.ray = {r.o[0], r.o[1], r.o[2], r.tmin, r.d[0], r.d[1], r.d[2], 0.0f, r.tmax, ~0u, 0, 0};
        rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
        rtcIntersect1(scene, &context, &rh);
        return rh.hit.geomID == RTC_INVALID_GEOMETRY_ID ? HitRecord{r.tmax, kNoPrimitive} : HitRecord{rh.ray.tfar, rh.hit.primID};
    }
    bool occluded(const RayRecord& r) const {
        RTCIntersectContext context;
        rtcInitIntersectContext(&context);
        RTCRay ray{r.o[0], r.o[1], r.o[2], r.tmin, r.d[0], r.d[1], r.d[2], 0.0f, r.tmax, ~0u, 0, 0};
        rtcOccluded1(scene, &context, &ray);
        return ray.tfar < 0;
    }
};

Ray to_ray(const RayRecord& r) { return Ray{{r.o[0], r.o[1], r.o[2]}, {r.d[0], r.d[1], r.d[2]}, r.tmin, r.tmax}; }

// Scene: Geometry or SplitGeometry.
template <typename Scene>
HitRecord glint_closest(const Scene& g, const RayRecord& r) {
    Hit hit;
    return g.intersect(to_ray(r), kNoPrimitive, hit) ? HitRecord{float(hit.t), hit.prim} : HitRecord{r.tmax, kNoPrimitive};
}

// FORMAT.md §4: the same primitive, or the same t within 1e-6 + 1e-4·t (ties at shared edges).
bool agree(const HitRecord& a, const HitRecord& b) {
    if ((a.prim == kNoPrimitive) != (b.prim == kNoPrimitive)) return false;
    if (a.prim == kNoPrimitive) return true;
    return std::fabs(a.t - b.t) <= 1e-6 + 1e-4 * std::max(a.t, b.t);
}

std::vector<std::string> g_build_rows, g_ray_rows;

template <typename... Args>
std::string format(const char* f, Args... args) {
    char line[512];
    std::snprintf(line, sizeof line, f, args...);
    return line;
}

// glint's two trees: the binned one and the one with spatial splits (spatial_splits.h).
struct GlintTrees {
    Geometry binned;
    SplitGeometry split;
};

// Build times and bytes per triangle of glint's two trees and Embree's two qualities: one row.
// Every build a fresh one (a single build also paid for set-up that later builds do not);
// Embree's timed around rtcCommitScene alone.
void bench_builds(const std::string& name, const ObjMesh& mesh, const std::vector<Triangle>& triangles,
                  GlintTrees& trees, const Embree* embree[2]) {
    const Times builds = interleaved_times({
        [&] { return seconds([&] { trees.binned = Geometry({}, triangles, Accelerator::bvh); }); },
        [&] { return seconds([&] { trees.split = SplitGeometry(triangles); }); },
        [&] { double s; const Embree scene(mesh, RTC_BUILD_QUALITY_MEDIUM, s); return s; },
        [&] { double s; const Embree scene(mesh, RTC_BUILD_QUALITY_HIGH, s); return s; },
    });
    const size_t n_tris = triangles.size();
    const auto per_triangle = [n_tris](size_t bytes) { return double(bytes) / double(n_tris); };
    const auto ms = [&](int e) { return median(builds[e]) * 1e3; };
    g_build_rows.push_back(format("| %s | %zu | %.1f / %.1f | %.1f / %.1f | %.2f / %.2f | %.1f / %.1f | %.1f / %.1f |", name.c_str(),
                                  n_tris, ms(0), ms(1), ms(2), ms(3), paired_ratio(builds[0], builds[2]), paired_ratio(builds[1], builds[3]), per_triangle(trees.binned.memory_bytes()),
                                  per_triangle(trees.split.memory_bytes()), per_triangle(embree[0]->bytes), per_triangle(embree[1]->bytes)));
}

// How many closest hits and occlusion answers of each glint tree differ from Embree MEDIUM's.
struct Disagreements {
    size_t closest[2] = {}, occluded[2] = {};
};

Disagreements check_answers(const std::vector<RayRecord>& rays, const GlintTrees& trees, const Embree& medium) {
    const size_t n = rays.size();
    std::vector<HitRecord> a(n), b(n);
    std::vector<char> o(n);
    Disagreements d;
    ThreadPool pool(2);
    for_rays(pool, n, [&](size_t i) { b[i] = medium.closest(rays[i]); o[i] = medium.occluded(rays[i]); });
    const auto count = [&](const auto& tree, int e) {
        for_rays(pool, n, [&](size_t i) { a[i] = glint_closest(tree, rays[i]); });
        for (size_t i = 0; i < n; ++i) {
            d.closest[e] += !agree(a[i], b[i]);
            d.occluded[e] += tree.occluded(to_ray(rays[i]), kNoPrimitive) != bool(o[i]);
        }
    };
    count(trees.binned, 0);
    count(trees.split, 1);
    return d;
}

// Each query on each engine (glint, glint split, MEDIUM, HIGH) with 1 and 2 threads, as seconds
// a pass: t[8q + 4(threads - 1) + engine], q 0 for closest hit and 1 for any hit.
Times time_queries(const std::vector<RayRecord>& rays, const GlintTrees& trees, const Embree* embree[2]) {
    const size_t n = rays.size();
    std::vector<HitRecord> hits(n);
    std::vector<char> occluded(n);
    ThreadPool one(1), two(2);
    const auto pass = [&](ThreadPool& pool, const std::function<void(size_t)>& f) {
        return [&pool, &f, n] { return seconds([&] { for_rays(pool, n, f); }); };
    };
    const std::function<void(size_t)> closest[4] = {
        [&](size_t i) { hits[i] = glint_closest(trees.binned, rays[i]); }, [&](size_t i) { hits[i] = glint_closest(trees.split, rays[i]); },
        [&](size_t i) { hits[i] = embree[0]->closest(rays[i]); }, [&](size_t i) { hits[i] = embree[1]->closest(rays[i]); }};
    const std::function<void(size_t)> any[4] = {
        [&](size_t i) { occluded[i] = trees.binned.occluded(to_ray(rays[i]), kNoPrimitive); },
        [&](size_t i) { occluded[i] = trees.split.occluded(to_ray(rays[i]), kNoPrimitive); },
        [&](size_t i) { occluded[i] = embree[0]->occluded(rays[i]); }, [&](size_t i) { occluded[i] = embree[1]->occluded(rays[i]); }};
    std::vector<std::function<double()>> runs;
    for (const auto* query : {closest, any})
        for (ThreadPool* pool : {&one, &two})
            for (int e = 0; e < 4; ++e) runs.push_back(pass(*pool, query[e]));
    return interleaved_times(runs);
}

// One table row per query: rays per second of every engine and thread count, glint's speed over
// Embree's on one thread (Embree's time over glint's; the best of each from each round's faster
// engine), and the disagreements with Embree MEDIUM.
void ray_rows(const std::string& set, size_t n, const Times& t, const Disagreements& d) {
    for (int q = 0; q < 2; ++q) {
        const std::vector<double>* one_thread = &t[8 * size_t(q)];
        const auto rate = [&](int threads, int e) { return double(n) / median(t[8 * size_t(q) + 4 * size_t(threads - 1) + size_t(e)]) / 1e6; };
        const auto fastest = [&](int e, int f) {
            std::vector<double> times(one_thread[e].size());
            for (size_t r = 0; r < times.size(); ++r) times[r] = std::min(one_thread[e][r], one_thread[f][r]);
            return times;
        };
        const double best = paired_ratio(fastest(2, 3), fastest(0, 1));
        const size_t* wrong = q == 0 ? d.closest : d.occluded;
        g_ray_rows.push_back(format("| %s | %s | %.2f / %.2f | %.2f / %.2f | %.2f / %.2f | %.2f / %.2f | %.2f | %.2f | %.2f | %zu / %zu |",
                                    set.c_str(), q == 0 ? "closest" : "any-hit", rate(1, 0), rate(2, 0), rate(1, 1), rate(2, 1),
                                    rate(1, 2), rate(2, 2), rate(1, 3), rate(2, 3), paired_ratio(one_thread[2], one_thread[0]),
                                    paired_ratio(one_thread[3], one_thread[1]), best, wrong[0], wrong[1]));
    }
}

void bench_mesh(const std::string& shared, const std::string& name) {
    const ObjMesh mesh = load_obj(shared + "/scenes/meshes/" + name + ".obj", size_t(1) << 30);
    const std::vector<Triangle> triangles = to_triangles(mesh);
    double unused;
    const Embree medium(mesh, RTC_BUILD_QUALITY_MEDIUM, unused);
    const Embree high(mesh, RTC_BUILD_QUALITY_HIGH, unused);
    const Embree* embree[2] = {&medium, &high};
    GlintTrees trees;
    bench_builds(name, mesh, triangles, trees, embree);
    for (const char* kind : {"primary", "diffuse"}) {
        const std::vector<RayRecord> rays = read_rays(shared + "/rays/" + name + "_" + kind + ".rays");
        const Disagreements d = check_answers(rays, trees, medium);
        ray_rows(name + "_" + kind, rays.size(), time_queries(rays, trees, embree), d);
    }
}

}  // namespace

int main(int argc, char** argv) {
    if (argc < 2) {
        std::fprintf(stderr, "usage: bvh_vs_embree SHARED_DIR [repeats]\n");
        return 2;
    }
    if (argc > 2) g_repeats = std::max(1, std::atoi(argv[2]));
    const std::string shared = argv[1];
    for (const char* mesh : {"bunny", "sponza_dabrovic", "cornell_box"}) bench_mesh(shared, mesh);
    std::printf("| mesh | triangles | glint build ms: binned / split | Embree ms: MEDIUM / HIGH | glint / Embree build time: binned / MEDIUM, split / HIGH | glint B/tri: binned / split | Embree B/tri: MEDIUM / HIGH |\n");
    std::printf("|---|---|---|---|---|---|---|\n");
    for (const auto& row : g_build_rows) std::printf("%s\n", row.c_str());
    std::printf("\nglint's triangle queries run in %s. Times and speeds are medians of %d interleaved rounds; each ratio\n"
                "is the median of the rounds' own ratios, the two runs it compares taken in the same round.\n",
                best_isa() == Isa::avx512 ? "AVX-512VL" : "AVX2", g_repeats);
    std::printf("\n| ray set | query | glint binned Mrays/s, 1 / 2 threads | glint split | Embree MEDIUM | Embree HIGH | binned / MEDIUM, 1 thread | split / HIGH | best glint / best Embree | answers differing from MEDIUM's: binned / split |\n");
    std::printf("|---|---|---|---|---|---|---|---|---|---|\n");
    for (const auto& row : g_ray_rows) std::printf("%s\n", row.c_str());
}
