#include "io/obj_loader.h"

#include <tiny_obj_loader.h>

#include <sstream>

#include "base/files.h"

namespace glint {
namespace {

// Hands tinyobjloader each library's text from the opener; an opener's failure is kept, to be
// thrown once the parser returns (an exception must not cross the library's code).
class LibraryReader : public tinyobj::MaterialReader {
public:
    explicit LibraryReader(const MtlOpener& open) : open_(open) {}

    bool operator()(const std::string& name, std::vector<tinyobj::material_t>* materials,
                    std::map<std::string, int>* ids, std::string* warning, std::string* error) override {
        std::string text;
        try {
            text = open_(name);
        } catch (const std::exception& e) {
            if (failure_.empty()) failure_ = "mtllib " + name + ": " + e.what();
            return false;
        }
        std::istringstream in(text);
        tinyobj::LoadMtl(ids, materials, &in, warning, error);
        return true;
    }
    const std::string& failure() const { return failure_; }

private:
    const MtlOpener& open_;
    std::string failure_;
};

std::vector<std::string> lines_of(const std::string& text) {
    std::vector<std::string> lines;
    std::istringstream in(text);
    for (std::string line; std::getline(in, line);)
        if (!line.empty()) lines.push_back(line);
    return lines;
}

void map_materials(const std::vector<tinyobj::material_t>& materials, ObjMesh& mesh) {
    try {
        for (const tinyobj::material_t& m : materials) mesh.materials.push_back(map_mtl_material(m));
    } catch (const MtlError& e) {
        throw ObjError(e.what());
    }
}

// Fan triangulation of every face, in file order, with each triangle's material when asked.
void add_faces(const std::vector<tinyobj::shape_t>& shapes, bool with_materials, ObjMesh& mesh) {
    const auto vertex_count = static_cast<int64_t>(mesh.vertices.size());
    const auto material_count = static_cast<int>(mesh.materials.size());
    for (const tinyobj::shape_t& shape : shapes) {
        size_t offset = 0;
        for (size_t face = 0; face < shape.mesh.num_face_vertices.size(); ++face) {
            const unsigned int face_size = shape.mesh.num_face_vertices[face];
            auto vertex = [&](size_t k) {
                const int index = shape.mesh.indices[offset + k].vertex_index;
                if (index < 0 || index >= vertex_count) throw ObjError("face refers to a missing vertex");
                return static_cast<uint32_t>(index);
            };
            const int id = shape.mesh.material_ids[face];
            const uint32_t material = id >= 0 && id < material_count ? uint32_t(id) : kNoObjMaterial;
            for (size_t k = 2; k < face_size; ++k) {
                mesh.triangles.push_back({vertex(0), vertex(k - 1), vertex(k)});
                if (with_materials) mesh.triangle_material.push_back(material);
            }
            offset += face_size;
        }
    }
}

}  // namespace

ObjMesh parse_obj(const std::string& text, const MtlOpener& open_mtl) {
    tinyobj::attrib_t attrib;
    std::vector<tinyobj::shape_t> shapes;
    std::vector<tinyobj::material_t> materials;
    std::string warning, error;
    std::istringstream in(text);
    LibraryReader reader(open_mtl);
    // No triangulation by the library: its quad split differs from the fan order the shared
    // ray sets number triangles by.
    const bool parsed = tinyobj::LoadObj(&attrib, &shapes, &materials, &warning, &error, &in,
                                         open_mtl ? &reader : nullptr, false);
    if (!reader.failure().empty()) throw ObjError(reader.failure());
    if (!parsed) throw ObjError(error.empty() ? "not a valid OBJ file" : error);
    ObjMesh mesh;
    if (open_mtl) mesh.warnings = lines_of(warning);
    mesh.vertices.reserve(attrib.vertices.size() / 3);
    for (size_t i = 0; i + 2 < attrib.vertices.size(); i += 3)
        mesh.vertices.push_back({attrib.vertices[i], attrib.vertices[i + 1], attrib.vertices[i + 2]});
    if (open_mtl) map_materials(materials, mesh);
    add_faces(shapes, bool(open_mtl), mesh);
    return mesh;
}

std::vector<Triangle> to_triangles(const ObjMesh& mesh, const Vec3& scale, const Vec3& translate) {
    auto place = [&](uint32_t index) { return mesh.vertices[index] * scale + translate; };
    std::vector<Triangle> out;
    out.reserve(mesh.triangles.size());
    for (const auto& t : mesh.triangles) out.push_back({place(t[0]), place(t[1]), place(t[2])});
    return out;
}

ObjMesh load_obj(const std::string& path, size_t max_bytes, const MtlOpener& open_mtl) {
    const std::vector<uint8_t> bytes = read_file(path, max_bytes);
    return parse_obj(std::string(bytes.begin(), bytes.end()), open_mtl);
}

}  // namespace glint
