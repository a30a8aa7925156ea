// Per-corner tangent frames for tangent-space normal maps, built as MikkTSpace builds them
// (the frame glTF 2.0 requires when a file gives no tangents): each triangle's tangent and
// bitangent from its UV derivatives, summed at each vertex over the triangles that share it
// (the same position, UV and normal, and the same handedness, so mirrored UVs do not cancel),
// weighted by the corner's angle, then made orthogonal to the vertex normal.
#pragma once

#include <vector>

#include "shapes/triangle.h"
#include "shapes/triangle_attributes.h"

namespace glint {

// The frames of `triangles` with their `uvs` and `normals` (one each per triangle; a triangle
// without normals takes its geometric normal).
std::vector<TriangleTangents> tangent_frames(const std::vector<Triangle>& triangles, const std::vector<TriangleUvs>& uvs,
                                             const std::vector<TriangleNormals>& normals);

}  // namespace glint
