// Triangles from Wavefront OBJ files, through Debian's tinyobjloader. Faces are fan-triangulated
// in file order, so triangle i is the i-th of ../shared/rays/FORMAT.md's numbering.
#pragma once

#include <array>
#include <stdexcept>
#include <string>
#include <vector>

#include "shapes/triangle.h"

namespace glint {

struct ObjError : std::runtime_error {
    using std::runtime_error::runtime_error;
};

struct ObjMesh {
    std::vector<Vec3> vertices;
    std::vector<std::array<uint32_t, 3>> triangles;
};

// Parses OBJ text. Material libraries are never opened: a scene reads no file it did not name.
ObjMesh parse_obj(const std::string& text);
// Reads and parses a file of at most max_bytes.
ObjMesh load_obj(const std::string& path, size_t max_bytes);

// The mesh's triangles in its numbering, each vertex placed at v·scale + translate.
std::vector<Triangle> to_triangles(const ObjMesh& mesh, const Vec3& scale = Vec3{1}, const Vec3& translate = {});

}  // namespace glint
