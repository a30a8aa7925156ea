// Triangles: a watertight ray test and the surface point it finds.
#pragma once

#include <immintrin.h>

#include <array>
#include <cmath>
#include <cstdint>
#include <utility>

#include "base/bounds.h"
#include "shapes/interaction.h"

namespace glint {

// Where a ray crosses a triangle: its parameter and the barycentric weights of v0, v1, v2.
struct TriangleHit {
    double t = kInfinity;
    double b0 = 0, b1 = 0, b2 = 0;
};

namespace detail {

// The 2D edge functions of Woop, Benthin and Wald ("Watertight ray/triangle intersection",
// JCGT 2013) after the ray has been sheared onto +z. Two triangles sharing an edge evaluate the
// identical expression for it, so a ray through the edge is inside at least one of them.
template <typename T>
inline void edge_functions(const T a[2], const T b[2], const T c[2], T& u, T& v, T& w) {
    u = c[0] * b[1] - c[1] * b[0];
    v = a[0] * c[1] - a[1] * c[0];
    w = b[0] * a[1] - b[1] * a[0];
}

}  // namespace detail

// The ray's share of the watertight test, the same for every triangle and so computed once per
// ray: the axis that becomes z, the shear that turns the direction onto it, and the origin in
// the permuted axes. The shear and the origin are kept as four-lane rows (lane 3 unused), which
// RunTest broadcasts from: a ray's set-up is a sizeable share of a short traversal's
// instructions, so it is paid once per ray rather than once per triangle run.
struct RayShear {
    int kx, ky, kz;
    alignas(32) double shear[4];   // sx, sy, sz: d[kx] / d[kz], d[ky] / d[kz], 1 / d[kz]
    alignas(32) double origin[4];  // ox, oy, oz: o[kx], o[ky], o[kz]

    double sx() const { return shear[0]; }
    double sy() const { return shear[1]; }
    double sz() const { return shear[2]; }
    double ox() const { return origin[0]; }
    double oy() const { return origin[1]; }
    double oz() const { return origin[2]; }

    explicit RayShear(const Ray& ray) {
        // Branch-free, as a diffuse ray's dominant axis is anyone's guess: the axes from tables
        // indexed by the three comparisons of max_axis(abs(d)) and by the sign along the chosen
        // axis, the direction and the origin put in the permuted order by one VPERMPS each, and
        // the three divisions in one instruction (each lane rounds as its scalar division would).
        const double ax = std::fabs(ray.d.x), ay = std::fabs(ray.d.y), az = std::fabs(ray.d.z);
        static constexpr int kDominant[8] = {2, 2, 2, 0, 1, 2, 1, 0};  // bits: ax > ay, ax > az, ay > az
        kz = kDominant[unsigned(ax > ay) | unsigned(ax > az) << 1 | unsigned(ay > az) << 2];
        const __m256d d = _mm256_setr_pd(ray.d.x, ray.d.y, ray.d.z, 0.0);
        // A negative dominant component swaps x and y, which keeps the winding, so the edge
        // functions' signs mean the same for every ray.
        const unsigned negative = static_cast<unsigned>(_mm256_movemask_pd(_mm256_cmp_pd(d, _mm256_setzero_pd(), _CMP_LT_OQ)));
        const Axes& axes = kAxes[2 * kz + (negative >> kz & 1)];
        kx = axes.x;
        ky = axes.y;
        const __m256i order = _mm256_load_si256(reinterpret_cast<const __m256i*>(axes.lanes));
        const auto permuted = [&](__m256d v) {
            return _mm256_castps_pd(_mm256_permutevar8x32_ps(_mm256_castpd_ps(v), order));
        };
        const __m256d pd = permuted(d);  // d[kx], d[ky], d[kz], d[kz]
        _mm256_store_pd(shear, _mm256_div_pd(_mm256_blend_pd(pd, _mm256_set1_pd(1.0), 0b1100), _mm256_permute4x64_pd(pd, 0xAA)));
        _mm256_store_pd(origin, permuted(_mm256_setr_pd(ray.o.x, ray.o.y, ray.o.z, 1.0)));  // lane 3: see FusedRayBoxTest::covers
    }

private:
    // For each dominant axis z and flip of x and y (index 2z + flip): the axes that become x
    // and y, and VPERMPS's indices that gather the doubles x, y, z, z of a vector.
    struct Axes {
        alignas(32) int32_t lanes[8];
        int x, y;
    };
    static constexpr std::array<Axes, 6> kAxes = [] {
        constexpr int kX[3][2] = {{1, 2}, {2, 0}, {0, 1}};
        std::array<Axes, 6> table{};
        for (int z = 0; z < 3; ++z)
            for (int flip = 0; flip < 2; ++flip) {
                Axes& a = table[2 * z + flip];
                a.x = kX[z][flip];
                a.y = 3 - z - a.x;
                const int gathered[4] = {a.x, a.y, z, z};
                for (int lane = 0; lane < 4; ++lane) {
                    a.lanes[2 * lane] = 2 * gathered[lane];
                    a.lanes[2 * lane + 1] = 2 * gathered[lane] + 1;
                }
            }
        return table;
    }();
};

namespace detail {

// Woop et al.'s test proper, given the vertices relative to the ray origin in the permuted axes
// (a[2] is along the ray's dominant axis). Two-sided, with no epsilon: a hit needs all three
// edge functions of one sign, and an edge function that is exactly zero (ray through an edge or
// vertex) counts as inside.
inline bool watertight_test(const double a[3], const double b[3], const double c[3], const RayShear& s,
                            const Ray& ray, TriangleHit& hit) {
    const double a2[2] = {a[0] - s.sx() * a[2], a[1] - s.sy() * a[2]};
    const double b2[2] = {b[0] - s.sx() * b[2], b[1] - s.sy() * b[2]};
    const double c2[2] = {c[0] - s.sx() * c[2], c[1] - s.sy() * c[2]};
    double u, v, w;
    edge_functions(a2, b2, c2, u, v, w);
    if (u == 0 || v == 0 || w == 0) {
        // Exactly on an edge in double: decide it with the wider long double, as the paper
        // redoes float in double, so that rounding alone never puts a ray on an edge.
        const long double la[2] = {a2[0], a2[1]}, lb[2] = {b2[0], b2[1]}, lc[2] = {c2[0], c2[1]};
        long double lu, lv, lw;
        edge_functions(la, lb, lc, lu, lv, lw);
        u = static_cast<double>(lu);
        v = static_cast<double>(lv);
        w = static_cast<double>(lw);
    }
    if ((u < 0 || v < 0 || w < 0) && (u > 0 || v > 0 || w > 0)) return false;
    const double det = u + v + w;
    if (det == 0) return false;  // the ray lies in the triangle's plane, or it is degenerate

    const double tz = u * (s.sz() * a[2]) + v * (s.sz() * b[2]) + w * (s.sz() * c[2]);
    const double inv_det = 1.0 / det;
    const double t = tz * inv_det;
    if (!(t > ray.tmin && t <= ray.tmax)) return false;
    hit = {t, u * inv_det, v * inv_det, w * inv_det};
    return true;
}

}  // namespace detail

struct Triangle {
    Vec3 v0, v1, v2;

    Bounds3 bounds() const {
        Bounds3 b;
        b.extend(v0);
        b.extend(v1);
        b.extend(v2);
        return b;
    }
    Vec3 unnormalized_normal() const { return cross(v1 - v0, v2 - v0); }
    double area() const { return 0.5 * length(unnormalized_normal()); }

    bool intersect(const Ray& ray, TriangleHit& hit) const { return intersect(ray, RayShear(ray), hit); }
    bool intersect(const Ray& ray, const RayShear& s, TriangleHit& hit) const {
        const double a[3] = {v0[s.kx] - s.ox(), v0[s.ky] - s.oy(), v0[s.kz] - s.oz()};
        const double b[3] = {v1[s.kx] - s.ox(), v1[s.ky] - s.oy(), v1[s.kz] - s.oz()};
        const double c[3] = {v2[s.kx] - s.ox(), v2[s.ky] - s.oy(), v2[s.kz] - s.oz()};
        return detail::watertight_test(a, b, c, s, ray, hit);
    }

    SurfaceInteraction interaction(const TriangleHit& hit, uint32_t prim) const;
};

// A triangle as the scene stores it: single-precision vertices (what OBJ files hold), 36 bytes
// against 72, so that twice as many fit in the cache. The tests and the shading still compute in
// double on the exactly widened vertices, so every bound above holds for the stored triangle.
struct PackedTriangle {
    float v[3][3];

    static PackedTriangle pack(const Triangle& t) {
        PackedTriangle p;
        const Vec3* vertices[3] = {&t.v0, &t.v1, &t.v2};
        for (int i = 0; i < 3; ++i)
            for (int a = 0; a < 3; ++a) p.v[i][a] = to_float_nearest((*vertices[i])[a]);
        return p;
    }
    Triangle unpack() const {
        return {{v[0][0], v[0][1], v[0][2]}, {v[1][0], v[1][1], v[1][2]}, {v[2][0], v[2][1], v[2][2]}};
    }
    // Bit for bit what unpack().intersect() answers, without building the double triangle.
    bool intersect(const Ray& ray, const RayShear& s, TriangleHit& hit) const {
        const double a[3] = {double(v[0][s.kx]) - s.ox(), double(v[0][s.ky]) - s.oy(), double(v[0][s.kz]) - s.oz()};
        const double b[3] = {double(v[1][s.kx]) - s.ox(), double(v[1][s.ky]) - s.oy(), double(v[1][s.kz]) - s.oz()};
        const double c[3] = {double(v[2][s.kx]) - s.ox(), double(v[2][s.ky]) - s.oy(), double(v[2][s.kz]) - s.oz()};
        return detail::watertight_test(a, b, c, s, ray, hit);
    }
};

// Triangles stored run by run, coordinate by coordinate: in a run of n (a BVH leaf, so at most
// four), coordinate a of vertex j of the run's i-th triangle is at run[(3j + a)·n + i], so that
// one load fetches that coordinate of all n triangles; a run of one is PackedTriangle's own
// layout. Still 36 bytes a triangle, with kPadding floats after the last run for the four-wide
// loads of a shorter run to read.
namespace triangle_run {

inline constexpr uint32_t kMaxSize = 4;
inline constexpr size_t kPadding = kMaxSize - 1;

inline PackedTriangle get(const float* run, uint32_t n, uint32_t i) {
    PackedTriangle p;
    const float* from = run + i;
    for (int j = 0; j < 3; ++j)
        for (int a = 0; a < 3; ++a, from += n) p.v[j][a] = *from;
    return p;
}

inline void put(float* run, uint32_t n, uint32_t i, const PackedTriangle& p) {
    for (int j = 0; j < 3; ++j)
        for (int a = 0; a < 3; ++a) run[(3 * j + a) * n + i] = p.v[j][a];
}

}  // namespace triangle_run

// The watertight test of PackedTriangle::intersect for the up to four triangles of a run at
// once, in AVX double precision, operation for operation the scalar one (nothing fused:
// CMakeLists.txt turns contraction off), so every value is bit for bit the scalar test's. A run
// in which some edge function is exactly zero goes to the scalar test, as only it has the
// long-double tie-break; NaN lanes fail every comparison, as they do in the scalar test.
class RunTest {
public:
    explicit RunTest(const RayShear& s)
        : axis_{uint32_t(s.kx), uint32_t(s.ky), uint32_t(s.kz)},
          origin_{_mm256_broadcast_sd(&s.origin[0]), _mm256_broadcast_sd(&s.origin[1]), _mm256_broadcast_sd(&s.origin[2])},
          sx_(_mm256_broadcast_sd(&s.shear[0])),
          sy_(_mm256_broadcast_sd(&s.shear[1])),
          sz_(_mm256_broadcast_sd(&s.shear[2])),
          shear_(s) {}

    // The hit that testing the run's triangles in order with PackedTriangle::intersect finds,
    // shrinking ray.tmax at each hit: the nearest, the last of equals. Lanes in `skip` are left
    // out. Returns the triangle's index in the run, or -1.
    [[gnu::always_inline]] int closest(const float* run, uint32_t n, unsigned skip, const Ray& ray, TriangleHit& hit) const {
        const Lanes l = lanes(run, n, skip);
        if (l.on_edge != 0) return scalar_closest(run, n, l.inside | l.on_edge, ray, hit);
        if (l.inside == 0) return -1;
        alignas(32) double t[4], u[4], v[4], w[4], inv_det[4];
        unsigned valid = in_range(l, ray, t, inv_det);
        if (valid == 0) return -1;
        _mm256_store_pd(u, l.u);
        _mm256_store_pd(v, l.v);
        _mm256_store_pd(w, l.w);
        // Usually one lane is hit; of several, in_range() left only t <= ray.tmax, so the scalar
        // tests in turn would keep the last of the nearest.
        int best = __builtin_ctz(valid);
        for (unsigned rest = valid & (valid - 1); rest != 0; rest &= rest - 1) {
            const int i = __builtin_ctz(rest);
            if (t[i] <= t[best]) best = i;
        }
        hit = {t[best], u[best] * inv_det[best], v[best] * inv_det[best], w[best] * inv_det[best]};
        return best;
    }

    // Whether one of the run's triangles outside `skip` is hit in (ray.tmin, ray.tmax].
    [[gnu::always_inline]] bool any(const float* run, uint32_t n, unsigned skip, const Ray& ray) const {
        const Lanes l = lanes(run, n, skip);
        TriangleHit unused;
        if (l.on_edge != 0) return scalar_closest(run, n, l.inside | l.on_edge, ray, unused) >= 0;
        if (l.inside == 0) return false;
        alignas(32) double t[4], inv_det[4];
        return in_range(l, ray, t, inv_det) != 0;
    }

private:
    struct Lanes {
        __m256d u, v, w, az, bz, cz;  // edge functions; vertices' distances along the ray's axis
        unsigned inside;   // all three edge functions of one sign (by sign bits: -0 negative, +0 positive)
        unsigned on_edge;  // some edge function exactly zero
    };

    Lanes lanes(const float* run, uint32_t n, unsigned skip) const {
        const uint32_t offset[3] = {axis_[0] * n, axis_[1] * n, axis_[2] * n};
        Lanes l;
        __m256d a[2], b[2], c[2];
        sheared(run, offset, a, l.az);
        sheared(run + 3 * n, offset, b, l.bz);
        sheared(run + 6 * n, offset, c, l.cz);
        l.u = _mm256_sub_pd(_mm256_mul_pd(c[0], b[1]), _mm256_mul_pd(c[1], b[0]));
        l.v = _mm256_sub_pd(_mm256_mul_pd(a[0], c[1]), _mm256_mul_pd(a[1], c[0]));
        l.w = _mm256_sub_pd(_mm256_mul_pd(b[0], a[1]), _mm256_mul_pd(b[1], a[0]));
        // The run's lanes by table: a shift by n would need n moved to cl first.
        static constexpr unsigned kRunLanes[triangle_run::kMaxSize + 1] = {0b0, 0b1, 0b11, 0b111, 0b1111};
        const unsigned used = kRunLanes[n] & ~skip;
        // One sign from the sign bits: u's differs from v's or w's where (u ^ v) | (u ^ w) has its
        // sign bit set. This holds for the lanes without zeros, and a zero sends the run to the
        // scalar test. A NaN lane's sign bit is arbitrary, but its t is NaN and fails in_range()
        // either way.
        const __m256d sign_differs = _mm256_or_pd(_mm256_xor_pd(l.u, l.v), _mm256_xor_pd(l.u, l.w));
        l.on_edge = any_compares<_CMP_EQ_OQ>(l) & used;
        l.inside = ~static_cast<unsigned>(_mm256_movemask_pd(sign_differs)) & used;
        return l;
    }

    template <int kCompare>
    static unsigned any_compares(const Lanes& l) {
        const __m256d zero = _mm256_setzero_pd();
        const __m256d any = _mm256_or_pd(_mm256_or_pd(_mm256_cmp_pd(l.u, zero, kCompare), _mm256_cmp_pd(l.v, zero, kCompare)),
                                         _mm256_cmp_pd(l.w, zero, kCompare));
        return static_cast<unsigned>(_mm256_movemask_pd(any));
    }

    // The lanes of `l.inside` whose t lies in (ray.tmin, ray.tmax], with every lane's t and
    // 1/det stored.
    unsigned in_range(const Lanes& l, const Ray& ray, double* t, double* inv_det) const {
        const __m256d det = _mm256_add_pd(_mm256_add_pd(l.u, l.v), l.w);
        const __m256d tz = _mm256_add_pd(_mm256_add_pd(_mm256_mul_pd(l.u, _mm256_mul_pd(sz_, l.az)),
                                                       _mm256_mul_pd(l.v, _mm256_mul_pd(sz_, l.bz))),
                                         _mm256_mul_pd(l.w, _mm256_mul_pd(sz_, l.cz)));
        const __m256d inv = _mm256_div_pd(_mm256_set1_pd(1.0), det);
        const __m256d tv = _mm256_mul_pd(tz, inv);
        const __m256d ok = _mm256_and_pd(_mm256_cmp_pd(tv, _mm256_set1_pd(ray.tmin), _CMP_GT_OQ),
                                         _mm256_cmp_pd(tv, _mm256_set1_pd(ray.tmax), _CMP_LE_OQ));
        _mm256_store_pd(t, tv);
        _mm256_store_pd(inv_det, inv);
        return static_cast<unsigned>(_mm256_movemask_pd(ok)) & l.inside;
    }

    // The scalar tests of the lanes in `lanes`, in order. Out of line and cold: rays meet an edge
    // function of exactly zero rarely, and inlined, the compiler hoists its shear values out of
    // the traversal loop, where they take registers the hot path needs and spill.
    [[gnu::noinline, gnu::cold]] int scalar_closest(const float* run, uint32_t n, unsigned lanes, const Ray& ray, TriangleHit& hit) const {
        Ray r = ray;
        int best = -1;
        for (; lanes != 0; lanes &= lanes - 1) {
            const int i = __builtin_ctz(lanes);
            if (!triangle_run::get(run, n, static_cast<uint32_t>(i)).intersect(r, shear_, hit)) continue;
            r.tmax = hit.t;
            best = i;
        }
        return best;
    }

    // One vertex of the run's triangles (its x coordinates at `vertex`, offset[k] floats on
    // to those along the ray's permuted axis k) relative to the origin: watertight_test's a,
    // sheared into `xy` (its a2) with its distance along the ray's axis in `z`.
    void sheared(const float* vertex, const uint32_t offset[3], __m256d xy[2], __m256d& z) const {
        __m256d p[3];
        for (int k = 0; k < 3; ++k) p[k] = _mm256_sub_pd(_mm256_cvtps_pd(_mm_loadu_ps(vertex + offset[k])), origin_[k]);
        xy[0] = _mm256_sub_pd(p[0], _mm256_mul_pd(sx_, p[2]));
        xy[1] = _mm256_sub_pd(p[1], _mm256_mul_pd(sy_, p[2]));
        z = p[2];
    }

    uint32_t axis_[3];
    __m256d origin_[3], sx_, sy_, sz_;
    const RayShear& shear_;
};

}  // namespace glint
