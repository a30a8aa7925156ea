#include "scene/material_maps.h"

#include <algorithm>

namespace glint {

void MaterialMaps::apply(Material& m, Uv uv) const {
    if (has(albedo)) m.albedo = min(max(albedo.rgb(uv.u, uv.v), Rgb{0}), Rgb{1});
    if (has(roughness)) m.roughness = std::clamp(roughness.value(uv.u, uv.v), kMinTexturedRoughness, 1.0);
    if (has(metallic)) m.metallic = std::clamp(metallic.value(uv.u, uv.v), 0.0, 1.0);
    if (has(emission)) m.emission = max(emission.rgb(uv.u, uv.v), Rgb{0});
}

Material MaterialMaps::everywhere(Material m) const {
    if (has(albedo)) m.albedo = min(max(albedo.scale, Rgb{0}), Rgb{1});
    if (has(roughness)) m.roughness = 1;
    if (has(metallic)) m.metallic = 0.5;
    if (has(emission)) m.emission = emission.scale;
    return m;
}

}  // namespace glint
