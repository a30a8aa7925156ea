// Triangles from Wavefront OBJ files, through Debian's tinyobjloader. Faces are fan-triangulated
// in file order, so triangle i is the i-th of ../shared/rays/FORMAT.md's numbering.
#pragma once

#include <array>
#include <functional>
#include <stdexcept>
#include <string>
#include <vector>

#include "io/mtl_material.h"
#include "shapes/triangle.h"
#include "shapes/triangle_attributes.h"

namespace glint {

struct ObjError : std::runtime_error {
    using std::runtime_error::runtime_error;
};

// The text of the material library a `mtllib` line names; throws (any std::exception, whose
// message the ObjError repeats) when it may not or cannot be read.
using MtlOpener = std::function<std::string(const std::string& name)>;

inline constexpr uint32_t kNoObjMaterial = ~0u;

struct ObjMesh {
    std::vector<Vec3> vertices;
    std::vector<std::array<uint32_t, 3>> triangles;
    // Each triangle's corners' texture coordinates (`vt`) and normals (`vn`): empty when the file
    // gives none; a triangle whose face gives none gets zero UVs or TriangleNormals' mark.
    std::vector<TriangleUvs> uvs;
    std::vector<TriangleNormals> normals;
    // When the libraries were read: their materials in file order, and each triangle's index
    // among them (kNoObjMaterial for faces under no `usemtl`, or one the libraries lack).
    std::vector<ObjMaterial> materials;
    std::vector<uint32_t> triangle_material;
    // What the parser noticed and went past (a `usemtl` naming no material, ...), one line each.
    std::vector<std::string> warnings;
};

// Parses OBJ text. Without `open_mtl`, material libraries are never opened (a scene reads no
// file it does not need) and triangle_material stays empty.
ObjMesh parse_obj(const std::string& text, const MtlOpener& open_mtl = {});
// Reads and parses a file of at most max_bytes.
ObjMesh load_obj(const std::string& path, size_t max_bytes, const MtlOpener& open_mtl = {});

// The mesh's triangles in its numbering, each vertex placed at v·scale + translate.
std::vector<Triangle> to_triangles(const ObjMesh& mesh, const Vec3& scale = Vec3{1}, const Vec3& translate = {});
// The mesh's normals as its triangles are placed by to_triangles (a normal scales by 1/scale).
std::vector<TriangleNormals> placed_normals(const ObjMesh& mesh, const Vec3& scale);

}  // namespace glint
