// A mesh file's own materials: read from its `mtllib` inside the scene's folder, overridden by
// name or all at once from the scene, and what glint cannot show named in a warning.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "assembly/scene_loader.h"
#include "support/image_files.h"

namespace glint {
namespace {

// Two quads under two materials, a face under none, and a library beside the OBJ.
constexpr const char* kObj =
    "mtllib two.mtl\n"
    "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\n"
    "f 1 2 3\n"                   // before any usemtl: the object's material
    "usemtl paint\nf 1 2 3 4\n"
    "usemtl lamp\nf 1 3 4\n";
constexpr const char* kMtl =
    "newmtl paint\nillum 2\nKd 0.5 0.4 0.3\nKs 0.2 0.2 0.2\nmap_Ks wood.png\n"
    "newmtl lamp\nKd 0 0 0\nKe 10 9 8\n"
    "newmtl unused\nillum 7\n";

std::string scene_error(const std::string& json, const std::filesystem::path& folder) {
    try {
        parse_scene(json, folder);
    } catch (const SceneError& e) {
        return e.what();
    }
    return "no error";
}

class ObjMaterials : public ::testing::Test {
protected:
    void SetUp() override {
        root_ = std::filesystem::temp_directory_path() / ("glint-mtl-test-" + std::to_string(::getpid()));
        std::filesystem::create_directories(root_ / "scene" / "meshes");
        write(root_ / "scene" / "meshes" / "two.obj", kObj);
        write(root_ / "scene" / "meshes" / "two.mtl", kMtl);
    }
    void TearDown() override { std::filesystem::remove_all(root_); }
    static void write(const std::filesystem::path& p, const std::string& text) { std::ofstream(p) << text; }
    LoadedScene load(const std::string& fields) const {
        return parse_scene(R"({"objects": [{"type": "mesh", "file": "meshes/two.obj")" + fields + "}]}", root_ / "scene");
    }
    std::string error_of(const std::string& fields) const {
        return scene_error(R"({"objects": [{"type": "mesh", "file": "meshes/two.obj")" + fields + "}]}", root_ / "scene");
    }
    std::filesystem::path root_;
};

TEST_F(ObjMaterials, EachUsemtlGroupGetsItsLibraryMaterial) {
    const LoadedScene s = load("");
    ASSERT_EQ(s.scene->geometry().primitive_count(), 4u);
    EXPECT_EQ(s.scene->material(0).albedo, Material{}.albedo);  // no usemtl: the default
    for (const uint32_t paint : {1u, 2u}) EXPECT_EQ(s.scene->material(paint).albedo, (Rgb{0.5, 0.4, 0.3}));
    EXPECT_EQ(s.scene->material(3).emission, (Rgb{10, 9, 8}));
    EXPECT_EQ(s.scene->lights().size(), 1u);  // the lamp's one triangle
    // Named, with the JSON path; the unused glass says nothing.
    const std::vector<std::string> warnings = {
        "objects[0].file: material \"paint\": ignored texture map_Ks wood.png"};
    EXPECT_EQ(s.warnings, warnings);
}

TEST_F(ObjMaterials, TheSceneOverridesAMaterialByNameFieldByField) {
    const LoadedScene s = load(R"(, "materials": {"lamp": {"emission": 17}, "paint": {"type": "mirror"}})");
    EXPECT_EQ(s.scene->material(3).emission, Rgb{17});
    EXPECT_EQ(s.scene->material(3).albedo, Rgb{0});  // kept from the library
    EXPECT_EQ(s.scene->material(1).type, MaterialType::mirror);
    EXPECT_EQ(s.scene->material(1).albedo, Rgb{1});  // a new type's own default
    const LoadedScene glass = load(R"(, "materials": {"paint": {"type": "glass", "ior": 1.33, "albedo": 0.9}})");
    EXPECT_DOUBLE_EQ(glass.scene->material(2).ior, 1.33);
    EXPECT_EQ(glass.scene->material(2).albedo, Rgb{0.9});
}

TEST_F(ObjMaterials, TheObjectsMaterialReplacesTheLibrary) {
    const LoadedScene s = load(R"(, "material": {"albedo": 0.2})");
    for (uint32_t p = 0; p < 4; ++p) EXPECT_EQ(s.scene->material(p).albedo, Rgb{0.2}) << p;
    EXPECT_EQ(s.scene->lights().size(), 0u);
    EXPECT_TRUE(s.warnings.empty());
    // ... and then `materials` still picks out one by name.
    const LoadedScene lit = load(R"(, "material": {"albedo": 0.2}, "materials": {"lamp": {"emission": 5}})");
    EXPECT_EQ(lit.scene->material(3).emission, Rgb{5});
    EXPECT_EQ(lit.scene->material(3).albedo, Rgb{0.2});
}

TEST_F(ObjMaterials, WithItsOwnMaterialTheLibraryIsNeverOpened) {
    std::filesystem::remove(root_ / "scene" / "meshes" / "two.mtl");
    EXPECT_EQ(error_of(R"(, "material": {"albedo": 0.2})"), "no error");
    EXPECT_EQ(error_of(R"(, "emission": 1)"), "no error");
    EXPECT_EQ(error_of("").rfind("objects[0].file: mtllib two.mtl: cannot open", 0), 0u) << error_of("");
}

TEST_F(ObjMaterials, BadOverridesNameTheirPath) {
    EXPECT_EQ(error_of(R"(, "materials": {"lamp": {"emision": 5}})"),
              "objects[0].materials.lamp.emision: unknown field (expected one of: type, albedo, ior, roughness, metallic, fresnel, "
              "alpha, alpha_cutoff, normal_map, emission)");
    EXPECT_EQ(error_of(R"(, "materials": {"lmap": {}})"),
              "objects[0].materials.lmap: the OBJ's material libraries have no material of this name");
    EXPECT_EQ(error_of(R"(, "materials": {"lamp": {"ior": 1.5}})"),
              "objects[0].materials.lamp.ior: only glass and plastic have an index of refraction");
    EXPECT_EQ(error_of(R"(, "materials": {"lamp": {"albedo": 2}})"), "objects[0].materials.lamp.albedo: must be in [0, 1]");
    EXPECT_EQ(error_of(R"(, "materials": [])"), "objects[0].materials: must be an object of material names");
    EXPECT_EQ(scene_error(R"({"objects": [{"type": "mesh", "vertices": [], "indices": [], "materials": {}}]})", {}),
              "objects[0].materials: only a mesh file's materials can be overridden by name");
}

TEST_F(ObjMaterials, LibrariesStayInsideTheScenesFolder) {
    write(root_ / "outside.mtl", "newmtl paint\nKd 1 0 0\n");
    std::filesystem::create_symlink(root_ / "outside.mtl", root_ / "scene" / "meshes" / "link.mtl");
    for (const std::string library : {"../../outside.mtl", "link.mtl"}) {
        write(root_ / "scene" / "meshes" / "two.obj", "mtllib " + library + "\n" + kObj);
        EXPECT_EQ(error_of(""), "objects[0].file: mtllib " + library + ": must stay inside the scene's folder");
    }
    write(root_ / "scene" / "meshes" / "two.obj", std::string("mtllib /etc/passwd\n") + kObj);
    EXPECT_EQ(error_of(""), "objects[0].file: mtllib /etc/passwd: must be relative to the OBJ's folder");
}

TEST_F(ObjMaterials, AUsemtlTheLibraryLacksTakesTheObjectsMaterialAndIsSaid) {
    write(root_ / "scene" / "meshes" / "two.obj", std::string(kObj) + "usemtl nothere\nf 1 2 3\n");
    const LoadedScene s = load(R"(, "materials": {"paint": {"albedo": 0.1}})");
    ASSERT_EQ(s.scene->geometry().primitive_count(), 5u);
    EXPECT_EQ(s.scene->material(4).albedo, Material{}.albedo);
    ASSERT_EQ(s.warnings.size(), 2u);
    EXPECT_NE(s.warnings[0].find("nothere"), std::string::npos) << s.warnings[0];
}

TEST_F(ObjMaterials, BadLibraryColoursAreErrors) {
    write(root_ / "scene" / "meshes" / "two.mtl", "newmtl paint\nKd 0.5 -1 0.5\n");
    EXPECT_EQ(error_of(""), "objects[0].file: material \"paint\": Kd must be in [0, 1e12]");
}

TEST(PublicScenes, CornellBoxOriginalGetsTheCornellMaterials) {
    if (!std::filesystem::exists(GLINT_SCENES_DIR "/meshes/cornell_box.obj"))
        GTEST_SKIP() << "run scenes/meshes/fetch.sh first";
    const LoadedScene s = load_scene(GLINT_SCENES_DIR "/cornell_box.json");
    EXPECT_TRUE(s.warnings.empty());
    ASSERT_EQ(s.scene->geometry().primitive_count(), 36u);
    // The OBJ's groups in file order: floor, ceiling, back wall, right (green), left (red), ...
    EXPECT_EQ(s.scene->material(0).albedo, (Rgb{0.725, 0.71, 0.68}));
    EXPECT_EQ(s.scene->material(6).albedo, (Rgb{0.14, 0.45, 0.091}));
    EXPECT_EQ(s.scene->material(8).albedo, (Rgb{0.63, 0.065, 0.05}));
    EXPECT_EQ(s.scene->lights().size(), 2u);
    EXPECT_EQ(s.scene->material(34).emission, (Rgb{17, 12, 4}));
}

}  // namespace
}  // namespace glint

namespace glint {
namespace {

// A quad with UVs whose library names textures as Blender's exporter writes them.
TEST(ObjTextures, TheLibrarysTexturesAreReadAsBlendersImporterReadsThem) {
    const testing::ScratchFolder folder("glint-obj-textures");
    std::filesystem::create_directories(folder.path() / "meshes" / "maps");
    std::ofstream(folder.path() / "meshes" / "quad.obj") << "mtllib quad.mtl\nv -1 -1 0\nv 1 -1 0\nv 1 1 0\nv -1 1 0\n"
                                                             "vt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\nvn 0 0 1\n"
                                                             "usemtl leaf\nf 1/1/1 2/2/1 3/3/1 4/4/1\n";
    std::ofstream(folder.path() / "meshes" / "quad.mtl") << "newmtl leaf\nKd 0.2 0.2 0.2\nKs 0.5 0.5 0.5\n"
                                                             "map_Kd -s 2 2 1 maps/colours.png\nmap_Pr maps/rough.png\n"
                                                             "map_d maps/mask.png\nmap_Ks maps/rough.png\n";
    // colours: black left, white right; rough: one grey texel; mask: grey, opaque at the bottom.
    folder.write("meshes/maps/colours.png", testing::png(2, 1, 1, {0, 255}));
    folder.write("meshes/maps/rough.png", testing::png(1, 1, 1, {51}));
    folder.write("meshes/maps/mask.png", testing::png(1, 2, 1, {0, 255}));
    const LoadedScene s = parse_scene(R"({"objects": [{"type": "mesh", "file": "meshes/quad.obj"}]})", folder.path());
    const std::vector<std::string> warnings = {"objects[0].file: material \"leaf\": ignored texture map_Ks maps/rough.png"};
    EXPECT_EQ(s.warnings, warnings);
    const Geometry& g = s.scene->geometry();
    const auto material_at = [&](double x, double y) {
        const Ray ray{{x, y, 2}, {0, 0, -1}};
        Hit hit;
        EXPECT_TRUE(g.intersect(ray, kNoPrimitive, hit)) << x << ", " << y;
        Material scratch;
        return s.scene->material_at(g.interaction(ray, hit), scratch);
    };
    // -s 2: u = 0.125 reads the texture at 0.25 (black), u = 0.375 at 0.75 (white).
    const Material black = material_at(-0.75, -0.9), white = material_at(-0.25, -0.9);
    EXPECT_EQ(black.type, MaterialType::plastic);
    EXPECT_EQ(black.albedo, Rgb{0});
    EXPECT_NEAR(white.albedo.y, 1, 1e-12);
    EXPECT_NEAR(black.roughness, 0.2, 1e-12);
    // map_d's grey (the image has no alpha): the top half is a hole.
    EXPECT_FALSE(g.occluded(Ray{{0, 0.9, 2}, {0, 0, -1}}, kNoPrimitive));
    EXPECT_TRUE(g.occluded(Ray{{0, -0.9, 2}, {0, 0, -1}}, kNoPrimitive));
    EXPECT_TRUE(g.smooth(g.triangle_id(0)));
}

TEST(ObjTextures, ALibrarysTexturesStayInsideTheScenesFolder) {
    const testing::ScratchFolder folder("glint-obj-texture-escape");
    std::ofstream(folder.path() / "quad.obj") << "mtllib quad.mtl\nv 0 0 0\nv 1 0 0\nv 1 1 0\nusemtl a\nf 1 2 3\n";
    std::ofstream(folder.path() / "quad.mtl") << "newmtl a\nKd 1 1 1\nmap_Kd ../../etc/passwd\n";
    const std::string error = scene_error(R"({"objects": [{"type": "mesh", "file": "quad.obj"}]})", folder.path());
    EXPECT_NE(error.find("objects[0].file: material \"a\": texture ../../etc/passwd: must stay inside the scene's folder"),
              std::string::npos) << error;
}

}  // namespace
}  // namespace glint
