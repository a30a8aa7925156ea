#include "shapes/tangent_frames.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <map>

namespace glint {
namespace {

// What makes two corners one vertex of the frames: position, UV, normal and handedness, bit for bit.
using CornerKey = std::array<float, 9>;

struct Sum {
    Vec3 tangent, bitangent;
};

Vec3 corner(const Triangle& t, int k) { return k == 0 ? t.v0 : k == 1 ? t.v1 : t.v2; }

Vec3 normal_of(const TriangleNormals& n, const Triangle& t, int k) {
    if (!n.present()) return normalize(t.unnormalized_normal());
    const Vec3 v{n.n[k][0], n.n[k][1], n.n[k][2]};
    const double l = length(v);
    return l > 0 && std::isfinite(l) ? v / l : normalize(t.unnormalized_normal());
}

// The triangle's dp/du and dp/dv, or false where its UVs are degenerate.
bool derivatives(const Triangle& t, const TriangleUvs& uv, Vec3& dpdu, Vec3& dpdv) {
    const double du1 = uv.uv[1][0] - uv.uv[0][0], dv1 = uv.uv[1][1] - uv.uv[0][1];
    const double du2 = uv.uv[2][0] - uv.uv[0][0], dv2 = uv.uv[2][1] - uv.uv[0][1];
    const double det = du1 * dv2 - du2 * dv1;
    if (!(std::fabs(det) > 0)) return false;
    const Vec3 e1 = t.v1 - t.v0, e2 = t.v2 - t.v0;
    dpdu = (e1 * dv2 - e2 * dv1) / det;
    dpdv = (e2 * du1 - e1 * du2) / det;
    return is_finite(dpdu) && is_finite(dpdv);
}

double corner_angle(const Triangle& t, int k) {
    const Vec3 p = corner(t, k), a = corner(t, (k + 1) % 3) - p, b = corner(t, (k + 2) % 3) - p;
    const double la = length(a), lb = length(b);
    if (!(la > 0 && lb > 0)) return 0;
    return std::acos(std::clamp(dot(a, b) / (la * lb), -1.0, 1.0));
}

CornerKey key_of(const Triangle& t, const TriangleUvs& uv, const Vec3& n, int k, float handedness) {
    const Vec3 p = corner(t, k);
    return {float(p.x), float(p.y), float(p.z), uv.uv[k][0], uv.uv[k][1], float(n.x), float(n.y), float(n.z), handedness};
}

}  // namespace

std::vector<TriangleTangents> tangent_frames(const std::vector<Triangle>& triangles, const std::vector<TriangleUvs>& uvs,
                                             const std::vector<TriangleNormals>& normals) {
    std::map<CornerKey, Sum> sums;
    std::vector<std::array<const CornerKey*, 3>> keys(triangles.size(), {nullptr, nullptr, nullptr});
    for (size_t i = 0; i < triangles.size(); ++i) {
        const Triangle& t = triangles[i];
        Vec3 dpdu, dpdv;
        if (!derivatives(t, uvs[i], dpdu, dpdv)) continue;
        const float handedness = dot(cross(t.unnormalized_normal(), dpdu), dpdv) < 0 ? -1.0f : 1.0f;
        for (int k = 0; k < 3; ++k) {
            const TriangleNormals none;
            const Vec3 n = normal_of(normals.empty() ? none : normals[i], t, k);
            auto [it, added] = sums.try_emplace(key_of(t, uvs[i], n, k, handedness));
            const double w = corner_angle(t, k);
            it->second.tangent += dpdu * w;
            it->second.bitangent += dpdv * w;
            keys[i][k] = &it->first;
        }
    }
    std::vector<TriangleTangents> out(triangles.size());
    for (size_t i = 0; i < triangles.size(); ++i)
        for (int k = 0; k < 3 && keys[i][0]; ++k) {
            const CornerKey& key = *keys[i][k];
            const Sum& s = sums.at(key);
            const Vec3 n{key[5], key[6], key[7]};
            const Vec3 t = s.tangent - n * dot(n, s.tangent);
            const double l = length(t);
            if (!(l > 0) || !std::isfinite(l)) continue;
            for (int a = 0; a < 3; ++a) out[i].t[k][a] = float(t[a] / l);
            out[i].t[k][3] = dot(cross(n, t), s.bitangent) < 0 ? -1.0f : 1.0f;
        }
    return out;
}

}  // namespace glint
