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

// A face's corner k as tinyobjloader indexes it, each index checked against what the file has.
struct Corner {
    uint32_t vertex;
    int uv, normal;  // -1: none
};

class FaceReader {
public:
    FaceReader(const tinyobj::attrib_t& attrib, const ObjMesh& mesh)
        : vertices_(int64_t(mesh.vertices.size())),
          uvs_(int64_t(attrib.texcoords.size() / 2)),
          normals_(int64_t(attrib.normals.size() / 3)),
          attrib_(attrib) {}

    Corner corner(const tinyobj::index_t& index) const {
        if (index.vertex_index < 0 || index.vertex_index >= vertices_) throw ObjError("face refers to a missing vertex");
        // A reference to a texture coordinate or normal the file lacks counts as none.
        return {uint32_t(index.vertex_index), index.texcoord_index < uvs_ ? index.texcoord_index : -1,
                index.normal_index < normals_ ? index.normal_index : -1};
    }
    bool has_uvs() const { return uvs_ > 0; }
    bool has_normals() const { return normals_ > 0; }

    TriangleUvs uvs(const Corner (&c)[3]) const {
        TriangleUvs t;
        for (int k = 0; k < 3; ++k)
            if (c[k].uv >= 0)
                for (int a = 0; a < 2; ++a) t.uv[k][a] = attrib_.texcoords[2 * size_t(c[k].uv) + a];
        return t;
    }
    // A face with a corner that gives no normal is shaded flat, as Blender's importer does.
    TriangleNormals normals(const Corner (&c)[3]) const {
        TriangleNormals t;
        for (int k = 0; k < 3; ++k)
            if (c[k].normal < 0) return TriangleNormals{};
        for (int k = 0; k < 3; ++k)
            for (int a = 0; a < 3; ++a) t.n[k][a] = attrib_.normals[3 * size_t(c[k].normal) + a];
        return t;
    }

private:
    int64_t vertices_, uvs_, normals_;
    const tinyobj::attrib_t& attrib_;
};

// Fan triangulation of every face, in file order, with each triangle's material when asked.
void add_faces(const tinyobj::attrib_t& attrib, const std::vector<tinyobj::shape_t>& shapes, bool with_materials,
               ObjMesh& mesh) {
    const FaceReader reader(attrib, mesh);
    const auto material_count = static_cast<int>(mesh.materials.size());
    for (const tinyobj::shape_t& shape : shapes) {
        size_t offset = 0;
        for (size_t face = 0; face < shape.mesh.num_face_vertices.size(); ++face) {
            const unsigned int face_size = shape.mesh.num_face_vertices[face];
            const auto corner = [&](size_t k) { return reader.corner(shape.mesh.indices[offset + k]); };
            const int id = shape.mesh.material_ids[face];
            const uint32_t material = id >= 0 && id < material_count ? uint32_t(id) : kNoObjMaterial;
            for (size_t k = 2; k < face_size; ++k) {
                const Corner c[3] = {corner(0), corner(k - 1), corner(k)};
                mesh.triangles.push_back({c[0].vertex, c[1].vertex, c[2].vertex});
                if (reader.has_uvs()) mesh.uvs.push_back(reader.uvs(c));
                if (reader.has_normals()) mesh.normals.push_back(reader.normals(c));
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
    add_faces(attrib, shapes, bool(open_mtl), mesh);
    return mesh;
}

std::vector<Triangle> to_triangles(const ObjMesh& mesh, const Vec3& scale, const Vec3& translate) {
    auto place = [&](uint32_t index) { return mesh.vertices[index] * scale + translate; };
    std::vector<Triangle> out;
    out.reserve(mesh.triangles.size());
    for (const auto& t : mesh.triangles) out.push_back({place(t[0]), place(t[1]), place(t[2])});
    return out;
}

std::vector<TriangleNormals> placed_normals(const ObjMesh& mesh, const Vec3& scale) {
    std::vector<TriangleNormals> out = mesh.normals;
    if (scale == Vec3{1}) return out;
    for (TriangleNormals& t : out)
        for (auto& n : t.n)
            for (int a = 0; a < 3; ++a) n[a] = float(n[a] / scale[a]);
    return out;
}

ObjMesh load_obj(const std::string& path, size_t max_bytes, const MtlOpener& open_mtl) {
    const std::vector<uint8_t> bytes = read_file(path, max_bytes);
    return parse_obj(std::string(bytes.begin(), bytes.end()), open_mtl);
}

}  // namespace glint
