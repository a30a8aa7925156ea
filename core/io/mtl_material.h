// Wavefront MTL materials mapped onto glint's three (docs/obj_materials.md has the table): what
// a material keeps, and what of it glint cannot show, so the loader can say so by name.
#pragma once

#include <stdexcept>
#include <string>
#include <vector>

#include "scene/material.h"

namespace tinyobj {
struct material_t;
}

namespace glint {

// A colour that is negative, not finite or, for emission, beyond kMaxMtlEmission.
struct MtlError : std::runtime_error {
    using std::runtime_error::runtime_error;
};

inline constexpr double kMaxMtlEmission = 1e12;

// A texture an MTL material names, with its -s and -o options (what Blender's importer puts in a
// Mapping node: the lookup at uv·scale + offset).
struct MtlTexture {
    std::string file;  // relative to the OBJ's folder; empty: none
    double uv_scale[2] = {1, 1}, uv_offset[2] = {0, 0};
};

// The textures of a material that glint reads, as Blender's OBJ importer connects them.
struct MtlTextures {
    MtlTexture albedo;     // map_Kd, in place of Kd
    MtlTexture roughness;  // map_Pr, or else map_Ns, read as roughness
    MtlTexture metallic;   // map_Pm
    MtlTexture alpha;      // map_d: a cut-out
    MtlTexture emission;   // map_Ke, in place of Ke
    MtlTexture normal;     // norm, or else map_Bump / bump: a tangent-space normal map
    double normal_strength = 1;  // its -bm
};

struct ObjMaterial {
    std::string name;
    Material material;
    MtlTextures textures;
    // What the library asks for that glint does not model (textures, glossy highlights, ...),
    // one phrase each; empty when the mapping is exact.
    std::vector<std::string> ignored;
};

ObjMaterial map_mtl_material(const tinyobj::material_t& mtl);

}  // namespace glint
