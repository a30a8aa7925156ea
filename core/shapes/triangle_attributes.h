// What a mesh gives its triangles besides positions: texture coordinates and vertex normals, per
// triangle corner, kept in single precision as the positions are. A scene whose meshes give
// neither stores nothing, and a triangle's shading reads them only when its scene has them.
#pragma once

#include <cmath>
#include <vector>

#include "base/math.h"

namespace glint {

struct Uv {
    double u = 0, v = 0;
};

struct TriangleUvs {
    float uv[3][2] = {};  // (u, v) of v0, v1, v2

    Uv at(double b1, double b2) const {
        const double b0 = 1 - b1 - b2;
        return {b0 * uv[0][0] + b1 * uv[1][0] + b2 * uv[2][0], b0 * uv[0][1] + b1 * uv[1][1] + b2 * uv[2][1]};
    }
};

struct TriangleNormals {
    // The normals of v0, v1, v2 (any length); NaN in n[0][0] marks a triangle without, which is
    // shaded by its geometric normal.
    float n[3][3] = {{NAN, 0, 0}, {}, {}};

    bool present() const { return !std::isnan(n[0][0]); }
    // The interpolated direction (not normalised), or zero where the corners' normals cancel.
    Vec3 at(double b1, double b2) const {
        const double b0 = 1 - b1 - b2;
        return Vec3{n[0][0], n[0][1], n[0][2]} * b0 + Vec3{n[1][0], n[1][1], n[1][2]} * b1 +
               Vec3{n[2][0], n[2][1], n[2][2]} * b2;
    }
};

// A corner's tangent for normal maps (shapes/tangent_frames.h builds them): its direction and
// the sign of the bitangent, cross(n, t)·sign.
struct TriangleTangents {
    float t[3][4] = {};  // xyz, sign; all zero: the triangle has none (degenerate UVs)

    bool present() const { return t[0][3] != 0; }
    // The interpolated tangent (not normalised); `sign` that of corner 0 (a triangle's corners
    // share their handedness).
    Vec3 at(double b1, double b2, double& sign) const {
        const double b0 = 1 - b1 - b2;
        sign = t[0][3];
        return Vec3{t[0][0], t[0][1], t[0][2]} * b0 + Vec3{t[1][0], t[1][1], t[1][2]} * b1 +
               Vec3{t[2][0], t[2][1], t[2][2]} * b2;
    }
};

// One entry per triangle, in the scene's triangle order, or none.
struct TriangleAttributes {
    std::vector<TriangleUvs> uvs;
    std::vector<TriangleNormals> normals;
    std::vector<TriangleTangents> tangents;  // where some material has a normal map
};

}  // namespace glint
