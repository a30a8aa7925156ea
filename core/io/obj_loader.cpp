#include "io/obj_loader.h"

#include <tiny_obj_loader.h>

#include <sstream>

#include "base/files.h"

namespace glint {

ObjMesh parse_obj(const std::string& text) {
    tinyobj::attrib_t attrib;
    std::vector<tinyobj::shape_t> shapes;
    std::vector<tinyobj::material_t> materials;
    std::string warning, error;
    std::istringstream in(text);
    // No MaterialReader: `mtllib` lines are ignored. No triangulation by the library: its
    // quad split differs from the fan order the shared ray sets number triangles by.
    if (!tinyobj::LoadObj(&attrib, &shapes, &materials, &warning, &error, &in, nullptr, false))
        throw ObjError(error.empty() ? "not a valid OBJ file" : error);
    ObjMesh mesh;
    mesh.vertices.reserve(attrib.vertices.size() / 3);
    for (size_t i = 0; i + 2 < attrib.vertices.size(); i += 3)
        mesh.vertices.push_back({attrib.vertices[i], attrib.vertices[i + 1], attrib.vertices[i + 2]});
    const auto vertex_count = static_cast<int64_t>(mesh.vertices.size());
    for (const tinyobj::shape_t& shape : shapes) {
        size_t offset = 0;
        for (const unsigned int face_size : shape.mesh.num_face_vertices) {
            auto vertex = [&](size_t k) {
                const int index = shape.mesh.indices[offset + k].vertex_index;
                if (index < 0 || index >= vertex_count) throw ObjError("face refers to a missing vertex");
                return static_cast<uint32_t>(index);
            };
            for (size_t k = 2; k < face_size; ++k) mesh.triangles.push_back({vertex(0), vertex(k - 1), vertex(k)});
            offset += face_size;
        }
    }
    return mesh;
}

std::vector<Triangle> to_triangles(const ObjMesh& mesh, const Vec3& scale, const Vec3& translate) {
    auto place = [&](uint32_t index) { return mesh.vertices[index] * scale + translate; };
    std::vector<Triangle> out;
    out.reserve(mesh.triangles.size());
    for (const auto& t : mesh.triangles) out.push_back({place(t[0]), place(t[1]), place(t[2])});
    return out;
}

ObjMesh load_obj(const std::string& path, size_t max_bytes) {
    const std::vector<uint8_t> bytes = read_file(path, max_bytes);
    return parse_obj(std::string(bytes.begin(), bytes.end()));
}

}  // namespace glint
