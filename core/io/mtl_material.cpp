#include "io/mtl_material.h"

#include <tiny_obj_loader.h>

#include <algorithm>
#include <charconv>
#include <cmath>
#include <tuple>

namespace glint {
namespace {

// tinyobjloader parses into float. The shortest decimal that reads back as that float is, for
// any value written with up to 6 significant digits, the one in the file: parsed as a double it
// gives the value a scene's JSON would (Kd 0.725 and "albedo": 0.725 render the same bits).
double widen(float v) {
    char text[32];
    const auto end = std::to_chars(text, text + sizeof text, v).ptr;
    double out = 0;
    std::from_chars(text, end, out);
    return out;
}

Rgb rgb(const tinyobj::real_t (&c)[3]) { return {widen(c[0]), widen(c[1]), widen(c[2])}; }

// Every colour the mapping reads, checked once: nothing negative, infinite or NaN goes on.
void check_colours(const tinyobj::material_t& mtl) {
    const std::pair<const tinyobj::real_t(*)[3], const char*> colours[] = {
        {&mtl.diffuse, "Kd"}, {&mtl.specular, "Ks"}, {&mtl.transmittance, "Tf"}, {&mtl.emission, "Ke"}};
    for (const auto& [c, key] : colours)
        for (const tinyobj::real_t v : *c)
            if (!(v >= 0 && v <= kMaxMtlEmission))
                throw MtlError("material \"" + mtl.name + "\": " + key + " must be in [0, 1e12]");
}

// A reflectance above 1 would create energy: clamped, and said.
Rgb reflectance(const Rgb& c, const char* key, ObjMaterial& out) {
    if (max_component(c) <= 1) return c;
    out.ignored.push_back(std::string(key) + " above 1 (clamped to 1)");
    return min(c, Rgb{1});
}

// MTL's illumination models 4, 6, 7 and 9 transmit light; so does any dissolve below 1, which
// is how most exporters mark glass. Tf alone does not: the MTL specification applies it only
// under those models, and exporters write `Tf 1 1 1` on opaque materials.
bool is_dielectric(const tinyobj::material_t& mtl) {
    return mtl.illum == 4 || mtl.illum == 6 || mtl.illum == 7 || mtl.illum == 9 || mtl.dissolve < 1;
}

// Illumination model 3 (ray-traced reflection), or a specular colour with no diffuse one.
bool is_mirror(const tinyobj::material_t& mtl) {
    return mtl.illum == 3 || (is_black(rgb(mtl.diffuse)) && !is_black(rgb(mtl.specular)));
}

// Roughness as Blender's OBJ importer reads it: the PBR extension's Pr where given, else
// 1 - sqrt(Ns / 1000) with Ns clamped to [0, 1000]. tinyobjloader gives an absent Ns as 1 and an
// absent Pr as 0, so Ns 1 reads as no Ns (a smooth surface), and Pr 0 as no Pr.
double roughness(const tinyobj::material_t& mtl) {
    if (mtl.roughness > 0) return std::min(1.0, widen(mtl.roughness));
    if (mtl.shininess == 1) return 0;
    return 1 - std::sqrt(std::clamp(widen(mtl.shininess), 0.0, 1000.0) / 1000);
}

// Kd with a specular colour, or with the PBR extension's roughness or metalness: glTF's
// dielectric (or, with Pm, its mix with the conductor).
bool is_plastic(const tinyobj::material_t& mtl) {
    return !is_black(rgb(mtl.specular)) || mtl.roughness > 0 || mtl.metallic > 0 || !mtl.roughness_texname.empty() ||
           !mtl.metallic_texname.empty();
}

MtlTexture texture(const std::string& file, const tinyobj::texture_option_t& options) {
    MtlTexture t;
    t.file = file;
    for (int a = 0; a < 2; ++a) {
        t.uv_scale[a] = widen(options.scale[a]);
        t.uv_offset[a] = widen(options.origin_offset[a]);
    }
    return t;
}

// The maps glint reads, where the material's type has the parameter (map_Kd: those whose
// albedo is Kd, which it replaces); the rest are named as ignored.
void map_textures(const tinyobj::material_t& mtl, ObjMaterial& out) {
    const MaterialType type = out.material.type;
    MtlTextures& t = out.textures;
    if (has_roughness(type)) {
        if (!mtl.roughness_texname.empty()) t.roughness = texture(mtl.roughness_texname, mtl.roughness_texopt);
        else if (!mtl.specular_highlight_texname.empty())
            t.roughness = texture(mtl.specular_highlight_texname, mtl.specular_highlight_texopt);
    }
    if (!mtl.metallic_texname.empty() && has_metallic(type)) t.metallic = texture(mtl.metallic_texname, mtl.metallic_texopt);
    if (!mtl.alpha_texname.empty()) t.alpha = texture(mtl.alpha_texname, mtl.alpha_texopt);
    if (!mtl.emissive_texname.empty()) t.emission = texture(mtl.emissive_texname, mtl.emissive_texopt);
    const bool norm = !mtl.normal_texname.empty();
    if (norm || !mtl.bump_texname.empty()) {
        const tinyobj::texture_option_t& options = norm ? mtl.normal_texopt : mtl.bump_texopt;
        t.normal = texture(norm ? mtl.normal_texname : mtl.bump_texname, options);
        t.normal_strength = std::clamp(widen(options.bump_multiplier), 0.0, 100.0);
    }
    const bool roughness_from_ns = !t.roughness.file.empty() && mtl.roughness_texname.empty();
    const std::tuple<const std::string&, const char*, bool> maps[] = {
        {mtl.diffuse_texname, "map_Kd", !t.albedo.file.empty()},
        {mtl.specular_texname, "map_Ks", false},
        {mtl.specular_highlight_texname, "map_Ns", roughness_from_ns},
        {mtl.roughness_texname, "map_Pr", !t.roughness.file.empty() && !roughness_from_ns},
        {mtl.metallic_texname, "map_Pm", !t.metallic.file.empty()},
        {mtl.bump_texname, "bump", !t.normal.file.empty() && !norm},
        {mtl.normal_texname, "norm", norm},
        {mtl.displacement_texname, "disp", false},
        {mtl.reflection_texname, "refl", false}};
    for (const auto& [name, key, read] : maps)
        if (!name.empty() && !read) out.ignored.push_back(std::string("texture ") + key + " " + name);
}

void map_glass(const tinyobj::material_t& mtl, ObjMaterial& out) {
    out.material.type = MaterialType::glass;
    out.material.roughness = roughness(mtl);
    const Rgb filter = rgb(mtl.transmittance);
    out.material.albedo = is_black(filter) ? Rgb{1} : reflectance(filter, "Tf", out);
    // tinyobjloader reads a missing Ni as 1, an index that would make the glass invisible.
    if (mtl.ior > 1 || (mtl.ior > 0 && mtl.ior < 1)) out.material.ior = widen(mtl.ior);
    else out.ignored.push_back("Ni 1 or none (glass uses 1.5)");
}

void map_mirror(const tinyobj::material_t& mtl, ObjMaterial& out) {
    out.material.type = MaterialType::mirror;
    out.material.roughness = roughness(mtl);
    const Rgb specular = rgb(mtl.specular);
    out.material.albedo = is_black(specular) ? Rgb{1} : reflectance(specular, "Ks", out);
    if (!is_black(rgb(mtl.diffuse))) out.ignored.push_back("Kd of a mirror");
}

void map_diffuse(const tinyobj::material_t& mtl, ObjMaterial& out) {
    out.material.type = MaterialType::diffuse;
    out.material.albedo = reflectance(rgb(mtl.diffuse), "Kd", out);
    if (!mtl.diffuse_texname.empty()) out.textures.albedo = texture(mtl.diffuse_texname, mtl.diffuse_texopt);
}

// The specular layer's colour is the dielectric's, from its index (1.5): Ks only marks it.
void map_plastic(const tinyobj::material_t& mtl, ObjMaterial& out) {
    out.material.type = MaterialType::plastic;
    out.material.albedo = reflectance(rgb(mtl.diffuse), "Kd", out);
    if (!mtl.diffuse_texname.empty()) out.textures.albedo = texture(mtl.diffuse_texname, mtl.diffuse_texopt);
    out.material.roughness = roughness(mtl);
    out.material.metallic = std::min(1.0, widen(mtl.metallic));
}

}  // namespace

ObjMaterial map_mtl_material(const tinyobj::material_t& mtl) {
    check_colours(mtl);
    ObjMaterial out{mtl.name, {}, {}, {}};
    if (is_dielectric(mtl)) map_glass(mtl, out);
    else if (is_mirror(mtl)) map_mirror(mtl, out);
    else if (is_plastic(mtl)) map_plastic(mtl, out);
    else map_diffuse(mtl, out);
    out.material.emission = rgb(mtl.emission);
    if (mtl.sheen > 0 || mtl.clearcoat_thickness > 0) out.ignored.push_back("sheen and clearcoat (Ps, Pc)");
    map_textures(mtl, out);
    return out;
}

}  // namespace glint
