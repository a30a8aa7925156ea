// What a surface is made of: a material's parameters, as a scene states them. What it does with
// light is its BSDF's (bsdf.h), built from these at a shading point.
#pragma once

#include "base/math.h"

namespace glint {

// smallpt's three materials, and glTF 2.0's metallic-roughness model at its two ends (metal and
// plastic, mixed by `metallic`).
enum class MaterialType { diffuse, mirror, glass, metal, plastic };

// How glass reflects: smallpt's Schlick approximation (with the cosine on the outer side), or the
// unpolarised dielectric Fresnel equations that Cycles, pbrt and Mitsuba use.
enum class FresnelModel { schlick, exact };

struct Material {
    MaterialType type = MaterialType::diffuse;
    Rgb albedo{0.75};
    double ior = 1.5;
    Rgb emission{0};  // radiance leaving both sides of the surface
    // Blender's and glTF's roughness r in [0, 1]; the GGX distribution's α is r².
    double roughness = 0;
    double metallic = 0;  // metal and plastic: glTF's mix of the conductor over the dielectric
    FresnelModel fresnel = FresnelModel::schlick;
    // The scene's maps of this material (scene/material_maps.h), or kNoMaps.
    uint32_t maps = kNoMaps;
    static constexpr uint32_t kNoMaps = ~0u;

    bool is_emissive() const { return !is_black(emission); }
};

// The scene file's name of each type, in MaterialType's order, and the type of a name among them.
inline constexpr const char* kMaterialTypeNames[] = {"diffuse", "mirror", "glass", "metal", "plastic"};
MaterialType material_type_named(const char* name);

// The scene file's defaults for a material of `type`: albedo 1 for mirror, glass and metal,
// metallic 1 for metal.
Material default_material(MaterialType type);
// Whether a material of `type` has the field: an index of refraction (glass, plastic), a
// roughness (all but diffuse), a metallic mix (metal, plastic), a Fresnel model (glass).
bool has_ior(MaterialType type);
bool has_roughness(MaterialType type);
bool has_metallic(MaterialType type);
bool has_fresnel(MaterialType type);

}  // namespace glint
