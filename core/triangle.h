// Triangles: a watertight ray test and the surface point it finds.
#pragma once

#include <utility>

#include "bounds.h"
#include "interaction.h"

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
// ray: the axis that becomes z, and the shear that turns the direction onto it.
struct RayShear {
    int kx, ky, kz;
    double sx, sy, sz;

    explicit RayShear(const Vec3& d) {
        kz = max_axis(abs(d));
        kx = kz == 2 ? 0 : kz + 1;
        ky = kx == 2 ? 0 : kx + 1;
        if (d[kz] < 0) std::swap(kx, ky);  // keep the winding, so the edge signs mean the same
        sx = d[kx] / d[kz];
        sy = d[ky] / d[kz];
        sz = 1.0 / d[kz];
    }
};

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

    // Two-sided, with no epsilon: a hit needs all three edge functions of one sign, and an
    // edge function that is exactly zero (ray through an edge or vertex) counts as inside.
    bool intersect(const Ray& ray, TriangleHit& hit) const { return intersect(ray, RayShear(ray.d), hit); }
    bool intersect(const Ray& ray, const RayShear& shear, TriangleHit& hit) const {
        const auto [kx, ky, kz, sx, sy, sz] = shear;
        const Vec3 a = v0 - ray.o, b = v1 - ray.o, c = v2 - ray.o;
        const double a2[2] = {a[kx] - sx * a[kz], a[ky] - sy * a[kz]};
        const double b2[2] = {b[kx] - sx * b[kz], b[ky] - sy * b[kz]};
        const double c2[2] = {c[kx] - sx * c[kz], c[ky] - sy * c[kz]};
        double u, v, w;
        detail::edge_functions(a2, b2, c2, u, v, w);
        if (u == 0 || v == 0 || w == 0) {
            // Exactly on an edge in double: decide it with the wider long double, as the paper
            // redoes float in double, so that rounding alone never puts a ray on an edge.
            const long double la[2] = {a2[0], a2[1]}, lb[2] = {b2[0], b2[1]}, lc[2] = {c2[0], c2[1]};
            long double lu, lv, lw;
            detail::edge_functions(la, lb, lc, lu, lv, lw);
            u = static_cast<double>(lu);
            v = static_cast<double>(lv);
            w = static_cast<double>(lw);
        }
        if ((u < 0 || v < 0 || w < 0) && (u > 0 || v > 0 || w > 0)) return false;
        const double det = u + v + w;
        if (det == 0) return false;  // the ray lies in the triangle's plane, or it is degenerate

        const double tz = u * (sz * a[kz]) + v * (sz * b[kz]) + w * (sz * c[kz]);
        const double inv_det = 1.0 / det;
        const double t = tz * inv_det;
        if (!(t > ray.tmin && t <= ray.tmax)) return false;
        hit = {t, u * inv_det, v * inv_det, w * inv_det};
        return true;
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
};

}  // namespace glint
