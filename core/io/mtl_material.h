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

struct ObjMaterial {
    std::string name;
    Material material;
    // What the library asks for that glint does not model (textures, glossy highlights, ...),
    // one phrase each; empty when the mapping is exact.
    std::vector<std::string> ignored;
};

ObjMaterial map_mtl_material(const tinyobj::material_t& mtl);

}  // namespace glint
