// glint's BVH against Embree 3 (Debian's libembree-dev; linked here only, never in glint) on the
// identical shared ray sets: build times, Mrays/s for closest and any-hit queries at 1 and 2
// threads, bytes per triangle, and whether the answers agree (ties at shared edges accepted, as
// ../shared/rays/FORMAT.md §4 says). Prints a markdown table.
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
#include "geometry.h"
#include "obj_loader.h"
#include "ray_file.h"
#include "thread_pool.h"

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

// Runs each of `runs` (each returns the seconds it measured) once a round, g_repeats rounds, and
// returns each one's median. Interleaved rather than one block per engine, so that a burst of load
// on this shared machine falls on every engine alike instead of on whichever ran during it.
std::vector<double> interleaved_medians(const std::vector<std::function<double()>>& runs) {
    std::vector<std::vector<double>> times(runs.size());
    for (int round = 0; round < g_repeats; ++round)
        for (size_t i = 0; i < runs.size(); ++i) times[i].push_back(runs[i]());
    std::vector<double> medians;
    for (const std::vector<double>& t : times) medians.push_back(median(t));
    return medians;
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

HitRecord glint_closest(const Geometry& g, const RayRecord& r) {
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

void bench_mesh(const std::string& shared, const std::string& name) {
    const ObjMesh mesh = load_obj(shared + "/scenes/meshes/" + name + ".obj", size_t(1) << 30);
    const std::vector<Triangle> triangles = to_triangles(mesh);
    const size_t n_tris = triangles.size();
    Geometry glint_bvh;
    // Every build a fresh one (a single build also paid for set-up that later builds do not);
    // Embree's timed around rtcCommitScene alone.
    const std::vector<double> builds = interleaved_medians({
        [&] { return seconds([&] { glint_bvh = Geometry({}, triangles, Accelerator::bvh); }); },
        [&] { double s; const Embree scene(mesh, RTC_BUILD_QUALITY_MEDIUM, s); return s; },
        [&] { double s; const Embree scene(mesh, RTC_BUILD_QUALITY_HIGH, s); return s; },
    });
    const double glint_build = builds[0], medium_build = builds[1], high_build = builds[2];
    const double glint_bytes = double(glint_bvh.memory_bytes()) / double(n_tris);
    double unused;
    const Embree medium(mesh, RTC_BUILD_QUALITY_MEDIUM, unused);
    const Embree high(mesh, RTC_BUILD_QUALITY_HIGH, unused);
    g_build_rows.push_back(format("| %s | %zu | %.1f | %.1f | %.1f | %.1f | %.1f | %.1f |", name.c_str(), n_tris, glint_build * 1e3,
                medium_build * 1e3, high_build * 1e3, glint_bytes, double(medium.bytes) / double(n_tris),
                double(high.bytes) / double(n_tris)));
    ThreadPool check_pool(2);
    for (const char* kind : {"primary", "diffuse"}) {
        const std::vector<RayRecord> rays = read_rays(shared + "/rays/" + name + "_" + kind + ".rays");
        const size_t n = rays.size();
        std::vector<HitRecord> a(n), b(n);
        for_rays(check_pool, n, [&](size_t i) {
            a[i] = glint_closest(glint_bvh, rays[i]);
            b[i] = medium.closest(rays[i]);
        });
        size_t disagree = 0, occlusion_disagree = 0;
        for (size_t i = 0; i < n; ++i) disagree += !agree(a[i], b[i]);
        for (size_t i = 0; i < n; ++i)
            occlusion_disagree += glint_bvh.occluded(to_ray(rays[i]), kNoPrimitive) != medium.occluded(rays[i]);
        std::vector<char> o(n);
        ThreadPool one(1), two(2);
        // Each query on each engine with 1 and 2 threads, as seconds a pass.
        const auto pass = [&](ThreadPool& pool, const std::function<void(size_t)>& f) {
            return [&pool, &f, n] { return seconds([&] { for_rays(pool, n, f); }); };
        };
        const std::function<void(size_t)> glint_c = [&](size_t i) { a[i] = glint_closest(glint_bvh, rays[i]); };
        const std::function<void(size_t)> medium_c = [&](size_t i) { b[i] = medium.closest(rays[i]); };
        const std::function<void(size_t)> high_c = [&](size_t i) { b[i] = high.closest(rays[i]); };
        const std::function<void(size_t)> glint_a = [&](size_t i) { o[i] = glint_bvh.occluded(to_ray(rays[i]), kNoPrimitive); };
        const std::function<void(size_t)> medium_a = [&](size_t i) { o[i] = medium.occluded(rays[i]); };
        const std::vector<double> t = interleaved_medians({pass(one, glint_c), pass(one, medium_c), pass(one, high_c),
                                                           pass(two, glint_c), pass(two, medium_c), pass(two, high_c),
                                                           pass(one, glint_a), pass(one, medium_a), pass(two, glint_a),
                                                           pass(two, medium_a)});
        std::vector<double> rate;  // Mrays/s, in the order above
        for (const double seconds_a_pass : t) rate.push_back(double(n) / seconds_a_pass / 1e6);
        g_ray_rows.push_back(format("| %s_%s | closest | %.2f / %.2f | %.2f / %.2f | %.2f / %.2f | %.2f | %zu |", name.c_str(),
                                    kind, rate[0], rate[3], rate[1], rate[4], rate[2], rate[5],
                                    rate[0] / std::max(rate[1], rate[2]), disagree));
        g_ray_rows.push_back(format("| %s_%s | any-hit | %.2f / %.2f | %.2f / %.2f | | %.2f | %zu |", name.c_str(), kind, rate[6],
                                    rate[8], rate[7], rate[9], rate[6] / rate[7], occlusion_disagree));
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
    std::printf("| mesh | triangles | glint build ms | Embree MEDIUM ms | Embree HIGH ms | glint B/tri | MEDIUM B/tri | HIGH B/tri |\n");
    std::printf("|---|---|---|---|---|---|---|---|\n");
    for (const auto& row : g_build_rows) std::printf("%s\n", row.c_str());
    std::printf("\nglint's triangle queries run in %s.\n", best_isa() == Isa::avx512 ? "AVX-512VL" : "AVX2");
    std::printf("\n| ray set | query | glint Mrays/s, 1 / 2 threads | Embree MEDIUM | Embree HIGH | glint / best Embree, 1 thread | answers that differ |\n");
    std::printf("|---|---|---|---|---|---|---|\n");
    for (const auto& row : g_ray_rows) std::printf("%s\n", row.c_str());
}
