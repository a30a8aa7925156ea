// The MTL → glint material mapping, one rule per test (docs/obj_materials.md has the table).
#include <gtest/gtest.h>

#include <sstream>
#include <tiny_obj_loader.h>

#include "io/mtl_material.h"

namespace glint {
namespace {

ObjMaterial mapped(const std::string& body) {
    std::map<std::string, int> ids;
    std::vector<tinyobj::material_t> materials;
    std::string warning, error;
    std::istringstream in("newmtl m\n" + body);
    tinyobj::LoadMtl(&ids, &materials, &in, &warning, &error);
    EXPECT_EQ(materials.size(), 1u);
    return map_mtl_material(materials.at(0));
}

TEST(MtlMaterial, KdIsTheDiffuseAlbedoAndKeTheEmission) {
    const ObjMaterial m = mapped("illum 1\nKa 0.1 0.1 0.1\nKd 0.5 0.25 0.125\nKe 17 12 4\n");
    EXPECT_EQ(m.material.type, MaterialType::diffuse);
    EXPECT_EQ(m.material.albedo, (Rgb{0.5, 0.25, 0.125}));
    EXPECT_EQ(m.material.emission, (Rgb{17, 12, 4}));
    EXPECT_TRUE(m.ignored.empty());  // Ka means nothing to a path tracer, and is not worth a word
}

TEST(MtlMaterial, MirrorsFromIllum3OrASpecularColourWithoutDiffuse) {
    const ObjMaterial by_illum = mapped("illum 3\nKs 0.9 0.9 0.9\n");
    EXPECT_EQ(by_illum.material.type, MaterialType::mirror);
    EXPECT_EQ(by_illum.material.albedo, Rgb{0.9});
    const ObjMaterial by_colour = mapped("illum 2\nKd 0 0 0\nKs 1 1 1\n");
    EXPECT_EQ(by_colour.material.type, MaterialType::mirror);
    EXPECT_EQ(by_colour.material.albedo, Rgb{1});
    EXPECT_EQ(mapped("illum 3\n").material.albedo, Rgb{1});
    EXPECT_EQ(mapped("illum 3\nKd 0.5 0.5 0.5\n").ignored, std::vector<std::string>{"Kd of a mirror"});
}

TEST(MtlMaterial, DielectricsFromTheirIllumModelsOrDissolveWithNi) {
    for (const int illum : {4, 6, 7, 9}) {
        const ObjMaterial m = mapped("illum " + std::to_string(illum) + "\nNi 1.33\n");
        EXPECT_EQ(m.material.type, MaterialType::glass) << illum;
        EXPECT_DOUBLE_EQ(m.material.ior, 1.33);
        EXPECT_EQ(m.material.albedo, Rgb{1});
    }
    const ObjMaterial dissolved = mapped("illum 2\nKd 0.8 0.8 0.8\nd 0.2\nNi 1.7\nTf 0.9 1 0.8\n");
    EXPECT_EQ(dissolved.material.type, MaterialType::glass);
    EXPECT_DOUBLE_EQ(dissolved.material.ior, 1.7);
    EXPECT_EQ(dissolved.material.albedo, (Rgb{0.9, 1, 0.8}));
    // Without Ni (tinyobjloader reads 1) the glass would vanish: 1.5, and a note.
    const ObjMaterial no_ni = mapped("illum 7\n");
    EXPECT_DOUBLE_EQ(no_ni.material.ior, 1.5);
    EXPECT_EQ(no_ni.ignored, std::vector<std::string>{"Ni 1 or none (glass uses 1.5)"});
}

TEST(MtlMaterial, TfAloneDoesNotMakeGlass) {
    // Exporters write `Tf 1 1 1` on opaque materials; the MTL specification uses Tf only under
    // the transmitting illumination models.
    EXPECT_EQ(mapped("illum 2\nKd 0.6 0.6 0.6\nTf 1 1 1\n").material.type, MaterialType::diffuse);
}

TEST(MtlMaterial, WhatGlintDoesNotModelIsNamed) {
    const ObjMaterial m = mapped("illum 2\nKd 1.5 0.5 0.5\nKs 0.3 0.3 0.3\nNs 50\nmap_Kd bricks.png\nbump bricks_bump.png\nPs 0.4\n");
    EXPECT_EQ(m.material.albedo, (Rgb{1, 0.5, 0.5}));
    const std::vector<std::string> expected = {"Kd above 1 (clamped to 1)", "sheen and clearcoat (Ps, Pc)"};
    EXPECT_EQ(m.ignored, expected);
    EXPECT_EQ(m.textures.albedo.file, "bricks.png");  // read: not named
    EXPECT_EQ(m.textures.normal.file, "bricks_bump.png");  // a normal map, as Blender's importer reads bump
    EXPECT_EQ(mapped("Kd 0.5 0.5 0.5\nPs 0.4\nPc 0.2\n").ignored, std::vector<std::string>{"sheen and clearcoat (Ps, Pc)"});
}

TEST(MtlMaterial, NsGivesRoughnessAsBlendersImporterAndKsWithKdAPlastic) {
    const ObjMaterial paint = mapped("illum 2\nKd 0.6 0.5 0.4\nKs 0.5 0.5 0.5\nNs 250\n");
    EXPECT_EQ(paint.material.type, MaterialType::plastic);
    EXPECT_EQ(paint.material.albedo, (Rgb{0.6, 0.5, 0.4}));
    EXPECT_DOUBLE_EQ(paint.material.roughness, 0.5);  // 1 - sqrt(250 / 1000)
    EXPECT_EQ(paint.material.metallic, 0);
    EXPECT_TRUE(paint.ignored.empty());
    EXPECT_DOUBLE_EQ(mapped("Kd 0.5 0.5 0.5\nKs 1 1 1\nNs 4000\n").material.roughness, 0);  // Ns clamped to 1000
    EXPECT_DOUBLE_EQ(mapped("Kd 0.5 0.5 0.5\nKs 1 1 1\nNs 0\n").material.roughness, 1);
    const ObjMaterial brushed = mapped("illum 3\nKs 0.9 0.9 0.9\nNs 640\n");
    EXPECT_EQ(brushed.material.type, MaterialType::mirror);
    EXPECT_DOUBLE_EQ(brushed.material.roughness, 0.2);
    EXPECT_EQ(mapped("illum 3\nKs 0.9 0.9 0.9\n").material.roughness, 0);  // no Ns: a polished mirror
    EXPECT_EQ(mapped("illum 1\nKd 0.5 0.5 0.5\nNs 10\n").material.type, MaterialType::diffuse);  // no Ks: no layer
}

TEST(MtlMaterial, ThePbrExtensionsRoughnessAndMetalnessWin) {
    const ObjMaterial m = mapped("Kd 0.9 0.6 0.2\nKs 0.5 0.5 0.5\nNs 900\nPr 0.3\nPm 0.8\n");
    EXPECT_EQ(m.material.type, MaterialType::plastic);
    EXPECT_FLOAT_EQ(float(m.material.roughness), 0.3f);
    EXPECT_FLOAT_EQ(float(m.material.metallic), 0.8f);
    const ObjMaterial frosted = mapped("illum 7\nNi 1.45\nPr 0.25\n");
    EXPECT_EQ(frosted.material.type, MaterialType::glass);
    EXPECT_DOUBLE_EQ(frosted.material.roughness, 0.25);
}

TEST(MtlMaterial, NegativeOrHugeColoursAreErrorsNamingTheMaterial) {
    EXPECT_THROW(mapped("Kd -0.5 0.5 0.5\n"), MtlError);
    try {
        mapped("Ke 1e30 0 0\n");
        ADD_FAILURE() << "no error";
    } catch (const MtlError& e) {
        EXPECT_STREQ(e.what(), "material \"m\": Ke must be in [0, 1e12]");
    }
}

}  // namespace
}  // namespace glint
