// One ray set through one or more engines in a plain loop on the calling thread, timed by the
// thread's CPU time: the step-by-step measurements of the BVH work (bench/BENCHMARKS.md) compare
// engines, or two builds of this, on the same set, and callgrind counts just the loop
// (`--toggle-collect='*trace_pass*'`).
//   ray_loop SHARED_DIR MESH KIND ENGINE[,ENGINE...] QUERY PASSES [LIMIT [DUMP]]
// MESH: a mesh of SHARED_DIR/scenes/meshes; KIND: primary | diffuse; ENGINE: glint | glint-split
// (glint's tree with spatial splits), either with -avx2 (its AVX2 path, not the widest) | medium |
// high (Embree's build qualities); QUERY: closest | any. Prints each engine's fastest pass.
// Several engines take turns pass by pass in the one process, and each after the first also gets
// the median over the passes of the first's speed over its own: on a shared machine whose speed
// drifts by a quarter within minutes, two passes a second apart see nearly the same machine.
// LIMIT traces only the first rays (0: all): a few
// thousand rays traced many times stay in the cache. DUMP writes the first engine's answers
// (closest: t, primitive and glint's barycentrics as doubles; any: 0 or 1), to compare two builds
// bit for bit with cmp. With RAY_LOOP_REPEAT=i in the environment, every ray traced is ray i of the
// set: its branches become predictable, which tells the cost of mispredicted branches from the
// rest. With RAY_LOOP_STATS=1, the trees' shapes are printed first: glint's by print_tree_stats(),
// Embree's by its own statistics (device option verbose=2).
#include <embree3/rtcore.h>

#include <algorithm>
#include <array>
#include <cstdlib>
#include <cstdio>
#include <ctime>
#include <memory>
#include <string>
#include <vector>

#include "embree_scene.h"
#include "spatial_splits.h"
#include "scene/geometry.h"
#include "io/obj_loader.h"
#include "io/ray_file.h"

using namespace glint;

namespace {

double thread_seconds() {
    timespec t{};
    clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
    return double(t.tv_sec) + 1e-9 * double(t.tv_nsec);
}

// Not inlined, so that callgrind can collect exactly the traced loop.
template <typename F>
[[gnu::noinline]] void trace_pass(F&& f) {
    f();
}

using Answer = std::array<double, 5>;

// The SAH's expected visits of a ray that meets the root's box (each box's surface area over the
// root's; leaves count as leaves, not by their triangles), Embree's measure in its statistics, and
// the counts behind them.
void print_tree_stats(const Bvh& bvh) {
    Bounds3 root;
    const BvhNode& top = bvh.nodes().front();
    for (int slot = 0; slot < kBvhWidth; ++slot)
        if (top.used(slot))
            for (int a = 0; a < 3; ++a) {
                root.lo[a] = std::min(root.lo[a], double(top.plane(2 * a, slot)));
                root.hi[a] = std::max(root.hi[a], double(top.plane(2 * a + 1, slot)));
            }
    double node_visits = 1, leaf_visits = 0;
    size_t children = 0, leaves = 0, references = 0;
    for (const BvhNode& n : bvh.nodes())
        for (int slot = 0; slot < kBvhWidth; ++slot) {
            if (!n.used(slot)) continue;
            ++children;
            const uint32_t count = ChildRef::count(n.child[slot]);
            (count > 0 ? leaf_visits : node_visits) += n.half_area(slot) / root.half_area();
            leaves += count > 0;
            references += count;
        }
    const size_t nodes = bvh.nodes().size();
    std::printf("tree: %zu nodes of %.2f children, %zu leaves of %.2f references; SAH visits: %.2f nodes, %.2f leaves\n",
                nodes, double(children) / double(nodes), leaves, double(references) / double(leaves), node_visits,
                leaf_visits);
}

// One engine with its structure built over the mesh, ready to trace the rays again and again.
class Engine {
public:
    virtual ~Engine() = default;
    // One timed pass over the rays, each answer stored; returns the thread's seconds.
    virtual double pass(const std::vector<RayRecord>& rays, bool closest, std::vector<Answer>& answers) const = 0;
};

// Times one pass of `trace(i, answer)` over the rays.
template <typename Trace>
double timed_pass(size_t n, std::vector<Answer>& answers, Trace&& trace) {
    const double start = thread_seconds();
    trace_pass([&] {
        for (size_t i = 0; i < n; ++i) trace(i, answers[i]);
    });
    return thread_seconds() - start;
}

// Scene: Geometry, or SplitGeometry for the tree with spatial splits (spatial_splits.h).
template <typename Scene>
class GlintEngine final : public Engine {
public:
    GlintEngine(Scene geometry, Isa isa) : geometry_(std::move(geometry)) {
        geometry_.set_isa(isa);
        if (std::getenv("RAY_LOOP_STATS")) print_tree_stats(geometry_.triangle_bvh());
    }
    double pass(const std::vector<RayRecord>& rays, bool closest, std::vector<Answer>& answers) const override {
        return timed_pass(rays.size(), answers, [&](size_t i, Answer& a) {
            const RayRecord& r = rays[i];
            const Ray ray{{r.o[0], r.o[1], r.o[2]}, {r.d[0], r.d[1], r.d[2]}, r.tmin, r.tmax};
            if (!closest) {
                a[0] = geometry_.occluded(ray, kNoPrimitive);
                return;
            }
            Hit hit;
            const bool found = geometry_.intersect(ray, kNoPrimitive, hit);
            a = {found ? hit.t : -1.0, found ? double(hit.prim) : -1.0, hit.triangle.b0, hit.triangle.b1, hit.triangle.b2};
        });
    }

private:
    Scene geometry_;
};

class EmbreeEngine final : public Engine {
public:
    EmbreeEngine(const ObjMesh& mesh, RTCBuildQuality quality)
        : device_(rtcNewDevice(std::getenv("RAY_LOOP_STATS") ? "threads=1,verbose=2" : "threads=1")),
          scene_(new_embree_scene(device_, mesh, quality)) {
        rtcCommitScene(scene_);
    }
    ~EmbreeEngine() override {
        rtcReleaseScene(scene_);
        rtcReleaseDevice(device_);
    }
    EmbreeEngine(const EmbreeEngine&) = delete;
    EmbreeEngine& operator=(const EmbreeEngine&) = delete;

    double pass(const std::vector<RayRecord>& rays, bool closest, std::vector<Answer>& answers) const override {
        return timed_pass(rays.size(), answers, [&](size_t i, Answer& a) {
            const RayRecord& r = rays[i];
            RTCIntersectContext context;
            rtcInitIntersectContext(&context);
            const RTCRay ray{r.o[0], r.o[1], r.o[2], r.tmin, r.d[0], r.d[1], r.d[2], 0.0f, r.tmax, ~0u, 0, 0};
            if (!closest) {
                RTCRay shadow = ray;
                rtcOccluded1(scene_, &context, &shadow);
                a[0] = shadow.tfar < 0;
                return;
            }
            RTCRayHit rh{};
            rh.ray = ray;
            rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
            rtcIntersect1(scene_, &context, &rh);
            const bool found = rh.hit.geomID != RTC_INVALID_GEOMETRY_ID;
            a = {found ? rh.ray.tfar : -1.0, found ? double(rh.hit.primID) : -1.0, 0, 0, 0};
        });
    }

private:
    RTCDevice device_;
    RTCScene scene_;
};

// glint's engines may end in -avx2: its AVX2 path where the processor has AVX-512VL.
std::unique_ptr<Engine> make_engine(std::string name, const ObjMesh& mesh) {
    const std::string avx2 = "-avx2";
    const bool want_avx2 = name.ends_with(avx2);
    if (want_avx2) name.resize(name.size() - avx2.size());
    const Isa isa = want_avx2 ? Isa::avx2 : best_isa();
    if (name == "glint") return std::make_unique<GlintEngine<Geometry>>(Geometry({}, to_triangles(mesh), Accelerator::bvh), isa);
    if (name == "glint-split") return std::make_unique<GlintEngine<SplitGeometry>>(SplitGeometry(to_triangles(mesh)), isa);
    if (!want_avx2 && (name == "medium" || name == "high"))
        return std::make_unique<EmbreeEngine>(mesh, name == "high" ? RTC_BUILD_QUALITY_HIGH : RTC_BUILD_QUALITY_MEDIUM);
    return nullptr;
}

double median(std::vector<double> v) {
    std::sort(v.begin(), v.end());
    return v[(v.size() - 1) / 2];
}

std::vector<std::string> split(const std::string& list) {
    std::vector<std::string> parts;
    for (size_t from = 0;;) {
        const size_t comma = list.find(',', from);
        parts.push_back(list.substr(from, comma - from));
        if (comma == std::string::npos) return parts;
        from = comma + 1;
    }
}

}  // namespace

int main(int argc, char** argv) {
    if (argc < 7) {
        std::fprintf(stderr, "usage: ray_loop SHARED_DIR MESH KIND ENGINE[,ENGINE...] closest|any PASSES [LIMIT [DUMP]]\n");
        return 2;
    }
    const std::string shared = argv[1], mesh_name = argv[2], kind = argv[3], query = argv[5];
    const int passes = std::max(1, std::atoi(argv[6]));
    const size_t limit = argc > 7 ? std::strtoull(argv[7], nullptr, 10) : 0;
    const ObjMesh mesh = load_obj(shared + "/scenes/meshes/" + mesh_name + ".obj", size_t(1) << 30);
    std::vector<RayRecord> rays = read_rays(shared + "/rays/" + mesh_name + "_" + kind + ".rays");
    if (limit > 0 && limit < rays.size()) rays.resize(limit);
    if (const char* repeat = std::getenv("RAY_LOOP_REPEAT")) std::fill(rays.begin(), rays.end(), rays.at(std::strtoull(repeat, nullptr, 10)));
    const std::vector<std::string> names = split(argv[4]);
    std::vector<std::unique_ptr<Engine>> engines;
    for (const std::string& name : names) {
        engines.push_back(make_engine(name, mesh));
        if (!engines.back()) {
            std::fprintf(stderr, "ray_loop: unknown engine '%s' (glint, glint-split, either with -avx2, medium or high)\n", name.c_str());
            return 2;
        }
    }
    // The engines' passes take turns, so that a slow spell of the machine falls on all of them.
    // Each engine writes answers of its own, and each round of passes starts one engine further
    // on, so that every engine takes every place in the order equally often: with the same order
    // every round, an identical copy placed after the first engine took 0.956-0.963 of its time.
    std::vector<std::vector<Answer>> answers(engines.size(), std::vector<Answer>(rays.size()));
    std::vector<std::vector<double>> seconds(engines.size());
    for (int p = 0; p < passes; ++p)
        for (size_t k = 0; k < engines.size(); ++k) {
            const size_t e = (size_t(p) + k) % engines.size();
            seconds[e].push_back(engines[e]->pass(rays, query == "closest", answers[e]));
        }
    for (size_t e = 0; e < engines.size(); ++e) {
        const double best = *std::min_element(seconds[e].begin(), seconds[e].end());
        std::printf("%s %s %s %s: %.6f s a pass (fastest of %d), %zu rays, %.1f ns a ray", mesh_name.c_str(), kind.c_str(),
                    names[e].c_str(), query.c_str(), best, passes, rays.size(), best / double(rays.size()) * 1e9);
        if (e > 0) {
            std::vector<double> ratio;
            for (int p = 0; p < passes; ++p) ratio.push_back(seconds[e][p] / seconds[0][p]);
            std::printf("; %s's speed over this one's, median of the passes' ratios: %.4f", names[0].c_str(), median(ratio));
        }
        std::printf("\n");
    }
    if (argc > 8) {
        std::FILE* f = std::fopen(argv[8], "wb");
        if (f == nullptr || std::fwrite(answers[0].data(), sizeof(Answer), rays.size(), f) != rays.size()) return 1;
        std::fclose(f);
    }
}
