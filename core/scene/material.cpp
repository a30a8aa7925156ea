#include "scene/material.h"

#include <cstring>
#include <iterator>

namespace glint {

MaterialType material_type_named(const char* name) {
    for (size_t i = 0; i < std::size(kMaterialTypeNames); ++i)
        if (std::strcmp(name, kMaterialTypeNames[i]) == 0) return static_cast<MaterialType>(i);
    return MaterialType::diffuse;
}

Material default_material(MaterialType type) {
    Material m;
    m.type = type;
    if (type != MaterialType::diffuse && type != MaterialType::plastic) m.albedo = Rgb{1};
    if (type == MaterialType::metal) m.metallic = 1;
    return m;
}

bool has_ior(MaterialType type) { return type == MaterialType::glass || type == MaterialType::plastic; }
bool has_roughness(MaterialType type) { return type != MaterialType::diffuse; }
bool has_metallic(MaterialType type) { return type == MaterialType::metal || type == MaterialType::plastic; }
bool has_fresnel(MaterialType type) { return type == MaterialType::glass; }

}  // namespace glint
