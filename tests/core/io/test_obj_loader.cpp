// OBJ numbering as ../shared/rays/FORMAT.md defines it, on small inputs and the shared meshes.
#include <gtest/gtest.h>

#include <filesystem>

#include "io/obj_loader.h"

namespace glint {
namespace {

TEST(ObjLoader, FanTriangulatesInFileOrderWithAllIndexForms) {
    const ObjMesh mesh = parse_obj(
        "# comment\r\n"
        "v 0 0 0\r\nv 1 0 0\r\nv 1 1 0\r\nv 0 1 0\r\nv 0 0 1 0.5\r\n"
        "mtllib /etc/passwd\r\n"          // never opened
        "f 1 2 3 4\r\n"                    // quad: (0,1,2), (0,2,3)
        "g second\r\n"
        "f 5/1 -4//2 -3/1/1\r\n"           // negative indices relative to the 5 vertices read
        "f 1 2\r\n");                      // fewer than 3 vertices: nothing
    ASSERT_EQ(mesh.vertices.size(), 5u);
    const std::vector<std::array<uint32_t, 3>> expected = {{0, 1, 2}, {0, 2, 3}, {4, 1, 2}};
    EXPECT_EQ(mesh.triangles, expected);
}

TEST(ObjLoader, RejectsFacesThatReferToMissingVertices) {
    EXPECT_THROW(parse_obj("v 0 0 0\nf 1 2 3\n"), ObjError);
}

TEST(ObjLoader, SharedMeshesHaveTheDocumentedTriangleCounts) {
    const std::filesystem::path meshes = GLINT_SHARED_DIR "/scenes/meshes";
    if (!std::filesystem::exists(meshes)) GTEST_SKIP() << "no ../shared/scenes/meshes here";
    EXPECT_EQ(load_obj((meshes / "cornell_box.obj").string(), 1 << 30).triangles.size(), 36u);
    EXPECT_EQ(load_obj((meshes / "bunny.obj").string(), 1 << 30).triangles.size(), 69451u);
    EXPECT_EQ(load_obj((meshes / "sponza_dabrovic.obj").string(), 1 << 30).triangles.size(), 66454u);
}

}  // namespace
}  // namespace glint
