// All the scene's surfaces, spheres and triangles in one primitive numbering, and the ray
// queries the integrator asks of them.
#pragma once

#include <functional>
#include <span>
#include <vector>

#include "accel/bvh.h"
#include "scene/alpha_mask.h"
#include "shapes/sphere.h"
#include "shapes/sphere_list.h"
#include "shapes/triangle.h"
#include "shapes/triangle_attributes.h"

namespace glint {

// `list` tests every primitive (smallpt's way); `automatic` picks it for scenes so small that a
// tree costs more than it saves (up to kListMaxPrimitives: testing them all is cheaper than a
// traversal's set-up and its node visits), else the BVH.
enum class Accelerator { automatic, bvh, list };
inline constexpr uint32_t kListMaxPrimitives = 16;

// The instruction set the triangle queries run in. Both paths compute 256-bit vectors and
// answer bit for bit alike; AVX-512VL's EVEX encoding gives them 32 vector registers instead of
// AVX2's 16, room for more of the box test's ray constants (GCC still loads some from the
// stack).
enum class Isa { avx2, avx512 };
// The widest this processor and its operating system support, found once per process.
Isa best_isa();

// The triangles' cut-outs: each triangle's mask among `masks`, or kNoMask.
struct CutOuts {
    std::vector<AlphaMask> masks;
    std::vector<uint32_t> mask_of_triangle;  // empty, or one per triangle
    static constexpr uint32_t kNoMask = ~0u;
};

struct Hit {
    double t = kInfinity;
    uint32_t prim = kNoPrimitive;
    TriangleHit triangle;  // barycentrics, when prim is a triangle
};

// Primitive ids: spheres take 0 .. S-1 in order, triangles S .. S+T-1. Triangle vertices are
// kept in single precision (PackedTriangle); everything reads them through triangle(), so the
// tests, the shading and the light sampling all see the same triangle.
//
// Spheres and triangles get a tree each: the triangles' tree stores them in its leaves' order,
// so a leaf reads one contiguous run with no index in between, and a scene of one kind pays
// nothing for the other.
// How the renderer's queries leave a ray's own triangle out of a leaf (geometry_queries.h).
struct LeaveOutByPosition;

class Geometry {
public:
    // Builds the triangles' tree over their boxes (triangle i's box is box i, empty for a
    // degenerate one): Bvh::build, or a benchmark's own build (bench/spatial_splits.h).
    using TriangleTreeBuild = std::function<Bvh(std::span<const Bounds3>)>;

    Geometry() = default;
    Geometry(std::vector<Sphere> spheres, const std::vector<Triangle>& triangles,
             Accelerator accelerator = Accelerator::automatic, const TriangleTreeBuild& build_triangle_tree = Bvh::build);

    size_t sphere_count() const { return spheres_.size(); }
    size_t triangle_count() const { return triangle_count_; }
    uint32_t primitive_count() const { return static_cast<uint32_t>(spheres_.size() + triangle_count_); }
    bool is_sphere(uint32_t prim) const { return prim < spheres_.size(); }
    const Sphere& sphere(uint32_t prim) const { return spheres_[prim]; }
    Triangle triangle(uint32_t prim) const { return packed(position(prim)).unpack(); }
    // The box around every primitive (computed on each call: for set-up, not for queries).
    Bounds3 bounds() const;
    uint32_t triangle_id(size_t triangle_index) const {
        return static_cast<uint32_t>(spheres_.size() + triangle_index);
    }
    const Bvh& sphere_bvh() const { return sphere_bvh_; }
    const Bvh& triangle_bvh() const { return triangle_bvh_; }
    // The trees, the packed triangles and the maps between primitive ids and tree order.
    size_t memory_bytes() const;
    // Zero-area triangles (collinear or coincident vertices): kept in the numbering, never hit.
    size_t degenerate_triangles() const { return degenerate_; }
    Accelerator accelerator() const { return accelerator_; }
    Isa isa() const { return isa_; }
    // Runs the triangle queries in `isa` (tests compare the paths); it must not exceed best_isa().
    void set_isa(Isa isa);
    // Gives the triangles their UVs and vertex normals (each list empty or one per triangle),
    // and their cut-outs, which every query then looks through.
    void attach(TriangleAttributes attributes, CutOuts cutouts = {});
    bool has_cutouts() const { return !cutouts_.masks.empty(); }
    const TriangleAttributes& attributes() const { return attributes_; }
    // Whether primitive `prim` is shaded by vertex normals.
    bool smooth(uint32_t prim) const {
        if (attributes_.normals.empty()) return false;
        const uint32_t index = triangle_index(prim);
        return index != kNoPrimitive && attributes_.normals[index].present();
    }
    // The texture coordinates at si: a triangle's interpolated UVs ((0, 0) where its mesh has
    // none); on a sphere, longitude and latitude as an equirectangular image maps them (u = 1/2
    // along +x, turning toward +z; v = 0 at the south pole).
    Uv uv(const SurfaceInteraction& si) const;
    // The tangent at si for a normal map (not normalised) and its bitangent's sign, or false
    // where the triangle has none (a sphere, or no UVs).
    bool tangent(const SurfaceInteraction& si, Vec3& t, double& sign) const;

    // Closest hit in (ray.tmin, ray.tmax]; `self` is the primitive the ray leaves from.
    // `LeaveOut`: how a leaf's test leaves `self` (and `target`) out (geometry_queries.h).
    template <typename LeaveOut = LeaveOutByPosition>
    bool intersect(const Ray& ray, uint32_t self, Hit& hit) const;
    // Whether anything other than `target` blocks the ray in (ray.tmin, ray.tmax].
    template <typename LeaveOut = LeaveOutByPosition>
    bool occluded(const Ray& ray, uint32_t self, uint32_t target = kNoPrimitive) const;
    SurfaceInteraction interaction(const Ray& ray, const Hit& hit) const;

    // Where triangle `prim` is stored (one of its positions in the tree's order, when there is
    // a tree), or kNoPrimitive when prim is not a triangle.
    uint32_t position(uint32_t prim) const {
        const uint32_t index = triangle_index(prim);
        return position_of_.empty() || index == kNoPrimitive ? index : position_of_[index];
    }
    // Triangle `prim`'s index among the triangles, or kNoPrimitive when prim is not a triangle.
    uint32_t triangle_index(uint32_t prim) const {
        if (prim < spheres_.size() || prim - spheres_.size() >= triangle_count_) return kNoPrimitive;
        return static_cast<uint32_t>(prim - spheres_.size());
    }
    // Tree position -> triangle index, with triangle_run::kPadding entries of kNoPrimitive
    // after the last (empty without a tree).
    std::span<const uint32_t> tree_order() const { return triangle_at_; }

private:
    // The triangle at `pos`: its run's size, its index in the run and where the run starts.
    uint32_t run_size(uint32_t pos) const { return run_slot_[pos] >> 4; }
    uint32_t run_index(uint32_t pos) const { return run_slot_[pos] & 15; }
    size_t run_start(uint32_t pos) const { return 9 * size_t(pos - run_index(pos)); }
    PackedTriangle packed(uint32_t pos) const {
        return triangle_run::get(&triangle_runs_[run_start(pos)], run_size(pos), run_index(pos));
    }
    void store_runs(const std::vector<PackedTriangle>& packed, const std::vector<uint32_t>& triangle_at);
    // The triangle queries, written once and instantiated for each Isa below.
    template <typename LeaveOut, bool kAvx512>
    [[gnu::always_inline]] bool closest_triangle(Ray& ray, uint32_t self, Hit& hit) const;
    template <typename LeaveOut>
    bool closest_triangle_avx2(Ray& ray, uint32_t self, Hit& hit) const;
    template <typename LeaveOut>
    [[gnu::target("avx512f,avx512vl")]] bool closest_triangle_avx512(Ray& ray, uint32_t self, Hit& hit) const;
    bool closest_sphere(Ray& ray, uint32_t self, Hit& hit) const;
    template <typename LeaveOut>
    [[gnu::always_inline]] bool triangle_blocks(const Ray& ray, uint32_t self, uint32_t target) const;
    template <typename LeaveOut>
    bool triangle_blocks_avx2(const Ray& ray, uint32_t self, uint32_t target) const;
    template <typename LeaveOut>
    [[gnu::target("avx512f,avx512vl")]] bool triangle_blocks_avx512(const Ray& ray, uint32_t self, uint32_t target) const;
    bool sphere_blocks(const Ray& ray, uint32_t self, uint32_t target) const;

    std::vector<Sphere> spheres_;
    SphereList sphere_list_;  // the spheres tested without a tree (Accelerator::list)
    // The triangles in triangle_bvh_'s order when there is a tree, each leaf's one run
    // (triangle_run layout), every other triangle a run of one.
    std::vector<float> triangle_runs_;
    std::vector<uint8_t> run_slot_;            // position -> run size << 4 | index in the run
    // Tree position -> triangle index (empty: identity), with triangle_run::kPadding entries of
    // kNoPrimitive after the last, for four-wide loads.
    std::vector<uint32_t> triangle_at_;
    std::vector<uint32_t> position_of_;        // triangle index -> tree position (empty: identity)
    Accelerator accelerator_ = Accelerator::bvh;  // never automatic once built
    Isa isa_ = best_isa();
    Bvh sphere_bvh_, triangle_bvh_;
    size_t triangle_count_ = 0;
    size_t degenerate_ = 0;
    TriangleAttributes attributes_;
    CutOuts cutouts_;
    // Whether a triangle hit falls in a hole of its cut-out.
    bool cut_away(const Hit& hit) const;
    // The closest triangle hit in the tree's instruction set.
    template <typename LeaveOut>
    bool closest_triangle_hit(Ray& ray, uint32_t self, Hit& hit) const;
    // The closest hit and the occlusion test where there are cut-outs: the tree's queries again
    // from each hit in a hole. Apart from the traversal, so that a scene without cut-outs runs
    // the code it ran before them.
    template <typename LeaveOut>
    bool closest_past_cutouts(Ray& ray, uint32_t self, Hit& hit) const;
    template <typename LeaveOut>
    bool blocked_past_cutouts(const Ray& ray, uint32_t self, uint32_t target) const;
};

}  // namespace glint
