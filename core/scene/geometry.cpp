#include "scene/geometry.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace glint {

Isa best_isa() {
    static const Isa best = [] {
        __builtin_cpu_init();  // may run before the constructor that would initialise the CPU model
        return __builtin_cpu_supports("avx512f") && __builtin_cpu_supports("avx512vl") ? Isa::avx512 : Isa::avx2;
    }();
    return best;
}

void Geometry::set_isa(Isa isa) {
    if (isa == Isa::avx512 && best_isa() != Isa::avx512) throw std::invalid_argument("this processor has no AVX-512VL");
    isa_ = isa;
}

Geometry::Geometry(std::vector<Sphere> spheres, const std::vector<Triangle>& triangles, Accelerator accelerator,
                   const TriangleTreeBuild& build_triangle_tree)
    : spheres_(std::move(spheres)), accelerator_(accelerator) {
    std::vector<PackedTriangle> packed;
    std::vector<Bounds3> triangle_bounds;
    packed.reserve(triangles.size());
    triangle_bounds.reserve(triangles.size());
    for (const Triangle& input : triangles) {
        packed.push_back(PackedTriangle::pack(input));
        const Triangle t = packed.back().unpack();
        // A zero-area triangle can never be hit (its determinant is 0): leave it out of the tree.
        // The squared length of the normal is positive exactly when the area is, without a root.
        const Vec3 n = t.unnormalized_normal();
        const bool degenerate = !(dot(n, n) > 0);
        degenerate_ += degenerate;
        triangle_bounds.push_back(degenerate ? Bounds3{} : t.bounds());
    }
    if (accelerator_ == Accelerator::automatic)
        accelerator_ = spheres_.size() + packed.size() <= kListMaxPrimitives ? Accelerator::list : Accelerator::bvh;
    if (accelerator_ != Accelerator::bvh) {
        sphere_list_ = SphereList(spheres_);
        store_runs(packed, {});
        return;
    }
    std::vector<Bounds3> sphere_bounds;
    sphere_bounds.reserve(spheres_.size());
    for (const Sphere& s : spheres_) sphere_bounds.push_back(s.bounds());
    sphere_bvh_ = Bvh::build(sphere_bounds);
    triangle_bvh_ = build_triangle_tree(triangle_bounds);
    triangle_at_ = triangle_bvh_.order();
    position_of_.resize(packed.size());
    for (uint32_t pos = 0; pos < triangle_at_.size(); ++pos) position_of_[triangle_at_[pos]] = pos;
    store_runs(packed, triangle_at_);
    triangle_at_.insert(triangle_at_.end(), triangle_run::kPadding, kNoPrimitive);
}

void Geometry::store_runs(const std::vector<PackedTriangle>& packed, const std::vector<uint32_t>& triangle_at) {
    triangle_count_ = packed.size();
    const size_t positions = triangle_at.empty() ? packed.size() : triangle_at.size();
    run_slot_.assign(positions, uint8_t{1 << 4});
    triangle_bvh_.for_each_leaf([&](uint32_t first, uint32_t count) {
        for (uint32_t i = 0; i < count; ++i) run_slot_[first + i] = static_cast<uint8_t>(count << 4 | i);
    });
    triangle_runs_.assign(9 * positions + triangle_run::kPadding, 0.0f);
    // In build order, the triangles' reads jump about: each is prefetched a few positions ahead,
    // a hint that costs an instruction against a cache miss on every large mesh.
    constexpr uint32_t kAhead = 16;
    for (uint32_t pos = 0; pos < positions; ++pos) {
        if (!triangle_at.empty() && pos + kAhead < positions) __builtin_prefetch(&packed[triangle_at[pos + kAhead]]);
        triangle_run::put(&triangle_runs_[run_start(pos)], run_size(pos), run_index(pos),
                          packed[triangle_at.empty() ? pos : triangle_at[pos]]);
    }
}

size_t Geometry::memory_bytes() const {
    return sphere_bvh_.memory_bytes() + sphere_bvh_.order().size() * sizeof(uint32_t) + triangle_bvh_.memory_bytes() +
           triangle_runs_.size() * sizeof(float) + run_slot_.size() +
           (triangle_at_.size() + position_of_.size()) * sizeof(uint32_t) +
           attributes_.uvs.size() * sizeof(TriangleUvs) + attributes_.normals.size() * sizeof(TriangleNormals);
}

static_assert(BinaryTree::kMaxLeafSize <= triangle_run::kMaxSize, "a leaf must fit one run test");

SurfaceInteraction Geometry::interaction(const Ray& ray, const Hit& hit) const {
    // One named result, built in place: a second return would copy the whole record.
    const bool sphere = is_sphere(hit.prim);
    SurfaceInteraction si = sphere ? spheres_[hit.prim].interaction(ray, hit.t, hit.prim)
                                   : triangle(hit.prim).interaction(hit.triangle, hit.prim);
    if (!sphere && !attributes_.normals.empty() && smooth(hit.prim)) {
        const Vec3 ns = attributes_.normals[triangle_index(hit.prim)].at(si.b1, si.b2);
        const double length2 = dot(ns, ns);
        // Corner normals that cancel, or overflow, leave the geometric normal.
        if (length2 > 0 && std::isfinite(length2)) {
            si.ns = dot(ns, si.n) < 0 ? -ns / std::sqrt(length2) : ns / std::sqrt(length2);
            si.shaded = true;
        }
    }
    return si;
}

void Geometry::attach(TriangleAttributes attributes, CutOuts cutouts) {
    const auto fits = [&](size_t n) { return n == 0 || n == triangle_count_; };
    if (!fits(attributes.uvs.size()) || !fits(attributes.normals.size()) || !fits(attributes.tangents.size()) ||
        !fits(cutouts.mask_of_triangle.size()))
        throw std::invalid_argument("triangle attributes: one per triangle or none");
    attributes_ = std::move(attributes);
    cutouts_ = std::move(cutouts);
    if (cutouts_.mask_of_triangle.empty()) cutouts_.masks.clear();
}

bool Geometry::tangent(const SurfaceInteraction& si, Vec3& t, double& sign) const {
    const uint32_t index = triangle_index(si.prim);
    if (index == kNoPrimitive || attributes_.tangents.empty() || !attributes_.tangents[index].present()) return false;
    t = attributes_.tangents[index].at(si.b1, si.b2, sign);
    return true;
}

Uv Geometry::uv(const SurfaceInteraction& si) const {
    if (is_sphere(si.prim)) {
        const Vec3 d = si.n;
        return {0.5 + std::atan2(d.z, d.x) / (2 * kPi), 0.5 + std::asin(std::clamp(d.y, -1.0, 1.0)) / kPi};
    }
    if (attributes_.uvs.empty()) return {};
    return attributes_.uvs[triangle_index(si.prim)].at(si.b1, si.b2);
}

Bounds3 Geometry::bounds() const {
    Bounds3 box;
    for (uint32_t prim = 0; prim < primitive_count(); ++prim)
        box.extend(is_sphere(prim) ? sphere(prim).bounds() : triangle(prim).bounds());
    return box;
}

}  // namespace glint
