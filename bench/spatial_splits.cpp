#include "spatial_splits.h"

#include <immintrin.h>

#include <algorithm>
#include <array>
#include <cmath>

#include "scene/geometry_queries.h"

namespace glint {
namespace {

// The planes tried per axis, evenly spaced over the node's box, and Stich et al.'s alpha: planes
// are looked for only where the object split's children overlap by more than this share of the
// root's half area, as below that they gain little for a costly search. More slabs find better
// planes for a longer sweep per node. Alpha above Stich et al.'s 1e-5 searches fewer nodes: a
// shorter build, for the few planes it misses in nodes whose children hardly overlap.
constexpr int kSpatialBins = 32;
constexpr float kOverlapShare = 1e-3f;

// Along one axis, kSpatialBins slabs of the node's box: each reference's part in each slab it
// crosses grows that slab's box, and it counts as entering its first slab and leaving its last.
// A plane between slabs has on its left the references entering before it and on its right
// those leaving after it: the cost sums their counts times their boxes' areas. Replaces `best`
// (cost, plane) where a plane on this axis costs less.
struct SlabBinning {
    std::span<const Triangle> triangles;
    std::span<const Bounds3> boxes;
    std::span<const uint32_t> prims;

    void best_on_axis(int a, const Bounds3& bounds, float& best_cost, SplitPlane& best) const {
        const double lo = bounds.lo[a], hi = bounds.hi[a];
        if (!(hi > lo) || !std::isfinite(hi - lo)) return;  // flat, or reaching infinity: no slabs
        const double scale = kSpatialBins / (hi - lo);
        const auto plane = [&](int b) { return lo + (hi - lo) * b / kSpatialBins; };
        const auto slab = [&](double x) { return std::clamp(int((x - lo) * scale), 0, kSpatialBins - 1); };
        // In double: rounding each part's box outward to float cost more than the rest of the
        // binning.
        std::array<Bounds3, kSpatialBins> slabs;
        std::array<uint32_t, kSpatialBins> entering{}, leaving{};
        for (size_t i = 0; i < boxes.size(); ++i) {
            const Bounds3& box = boxes[i];
            const int first = slab(box.lo[a]), last = slab(box.hi[a]);
            ++entering[first];
            ++leaving[last];
            if (first == last) {
                slabs[first].extend(box);
                continue;
            }
            // Estimated: the triangle's part in each slab, cut down to the reference's box.
            const Triangle& triangle = triangles[prims[i]];
            for (int b = first; b <= last; ++b) slabs[b].extend(overlap(slab_bounds(triangle, a, plane(b), plane(b + 1)), box));
        }
        std::array<double, kSpatialBins> right_cost{};
        Bounds3 acc;
        uint32_t n = 0;
        for (int b = kSpatialBins - 1; b > 0; --b) {
            acc.extend(slabs[b]);
            n += leaving[b];
            right_cost[b] = n > 0 ? acc.half_area() * n : kInfinity;
        }
        acc = {};
        n = 0;
        for (int b = 0; b + 1 < kSpatialBins; ++b) {
            acc.extend(slabs[b]);
            n += entering[b];
            const auto cost = static_cast<float>(acc.half_area() * n + right_cost[b + 1]);
            if (n > 0 && cost < best_cost) {
                best_cost = cost;
                best = {a, plane(b + 1)};
            }
        }
    }
};

// A convex polygon of at most 9 corners: a triangle cut by the six planes of a box.
struct Polygon {
    std::array<Vec3, 9> corners;
    int size = 0;
};

// Sutherland and Hodgman's step: the part of `in` on one side of an axis plane (side +1:
// coordinate >= plane, -1: <= plane). A crossing gets the plane's coordinate exactly.
Polygon clip(const Polygon& in, int axis, double plane, double side) {
    Polygon out;
    for (int i = 0; i < in.size; ++i) {
        const Vec3& a = in.corners[i];
        const Vec3& b = in.corners[(i + 1) % in.size];
        const double da = (a[axis] - plane) * side, db = (b[axis] - plane) * side;
        if (da >= 0) out.corners[out.size++] = a;
        if ((da < 0 && db > 0) || (da > 0 && db < 0)) {
            Vec3 q = a + (b - a) * (da / (da - db));
            q[axis] = plane;
            out.corners[out.size++] = q;
        }
    }
    return out;
}

// The triangles as Geometry stores them: their vertices rounded to float (PackedTriangle).
std::vector<Triangle> stored_triangles(const std::vector<Triangle>& triangles) {
    std::vector<Triangle> stored;
    stored.reserve(triangles.size());
    for (const Triangle& t : triangles) stored.push_back(PackedTriangle::pack(t).unpack());
    return stored;
}

}  // namespace

float SpatialSplits::overlap_share() const { return kOverlapShare; }

float SpatialSplits::best_plane(std::span<const Bounds3> boxes, std::span<const uint32_t> prims,
                                  const Bounds3& node, SplitPlane& plane) const {
    const SlabBinning binning{triangles_, boxes, prims};
    float cost = std::numeric_limits<float>::infinity();
    for (int a = 0; a < 3; ++a) binning.best_on_axis(a, node, cost, plane);
    return cost;
}

Bounds3 SpatialSplits::part(uint32_t prim, const Bounds3& box) const { return clipped_bounds(triangles_[prim], box); }

unsigned LeaveOutByIndex::lanes(const Geometry& geometry, uint32_t key, uint32_t first) {
    if (key == kNoPrimitive) return 0;  // a camera ray's, and the shared ray sets': no load
    const __m128i indices = _mm_loadu_si128(reinterpret_cast<const __m128i*>(&geometry.tree_order()[first]));
    const __m128i same = _mm_cmpeq_epi32(indices, _mm_set1_epi32(static_cast<int>(key)));
    return static_cast<unsigned>(_mm_movemask_ps(_mm_castsi128_ps(same)));
}

SplitGeometry::SplitGeometry(const std::vector<Triangle>& triangles) {
    const std::vector<Triangle> stored = stored_triangles(triangles);
    const SpatialSplits splits(stored);
    geometry_ = Geometry({}, triangles, Accelerator::bvh, [&](std::span<const Bounds3> boxes) {
        return Bvh::from_tree(build_sah_tree(boxes, splits), boxes);
    });
}

bool SplitGeometry::intersect(const Ray& ray, uint32_t self, Hit& hit) const {
    return geometry_.intersect<LeaveOutByIndex>(ray, self, hit);
}

bool SplitGeometry::occluded(const Ray& ray, uint32_t self, uint32_t target) const {
    return geometry_.occluded<LeaveOutByIndex>(ray, self, target);
}

Bounds3 clipped_bounds(const Triangle& t, const Bounds3& box) {
    Polygon p;
    p.corners = {t.v0, t.v1, t.v2};
    p.size = 3;
    for (int a = 0; a < 3 && p.size > 0; ++a) {
        p = clip(p, a, box.lo[a], +1);
        p = clip(p, a, box.hi[a], -1);
    }
    Bounds3 part;
    for (int i = 0; i < p.size; ++i) part.extend(p.corners[i]);
    if (part.empty()) return part;
    // Every corner is a weighted mean of the vertices, so their largest coordinate bounds every
    // corner's; six cuts round each crossing a few times in the 53rd bit of that magnitude.
    // 2^-40 of it is far beyond that error and far below a float unit. The part lies in the box.
    const Vec3 m = max(max(abs(t.v0), abs(t.v1)), abs(t.v2));
    const Vec3 pad{0x1p-40 * std::max({m.x, m.y, m.z})};
    part.lo = max(part.lo - pad, box.lo);
    part.hi = min(part.hi + pad, box.hi);
    return part;
}

Bounds3 slab_bounds(const Triangle& t, int axis, double lower, double upper) {
    const Vec3* v[3] = {&t.v0, &t.v1, &t.v2};
    Bounds3 part;
    for (int i = 0; i < 3; ++i) {
        const Vec3& a = *v[i];
        const Vec3& b = *v[(i + 1) % 3];
        if (a[axis] >= lower && a[axis] <= upper) part.extend(a);
        // The edge from a to b crosses each plane strictly between its ends at most once.
        for (const double plane : {lower, upper}) {
            if ((a[axis] < plane && plane < b[axis]) || (b[axis] < plane && plane < a[axis])) {
                Vec3 q = a + (b - a) * ((plane - a[axis]) / (b[axis] - a[axis]));
                q[axis] = plane;
                part.extend(q);
            }
        }
    }
    return part;
}

}  // namespace glint
