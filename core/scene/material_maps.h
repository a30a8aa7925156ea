// The parameters of a material that image textures give, looked up at a surface point's UVs,
// and the maps of its surface: a cut-out and a tangent-space normal map. A material without maps
// pays nothing: the integrator asks for them only where Material::maps names some.
#pragma once

#include "scene/alpha_mask.h"
#include "scene/material.h"

namespace glint {

// The least roughness a texture gives: just above Ggx's smooth threshold, so that a textured
// surface is glossy everywhere, as the integrator's choice of strategies (per material) assumes.
inline constexpr double kMinTexturedRoughness = 0.032;

struct MaterialMaps {
    // Each replaces the material's own value where its texture is set.
    TextureLookup albedo, roughness, metallic, emission;
    AlphaMask alpha;
    // A tangent-space normal map (linear; x and y multiplied by normal_strength, glTF's scale).
    TextureLookup normal;
    double normal_strength = 1;

    bool has(const TextureLookup& map) const { return map.texture != nullptr; }
    // Whether any of the material's parameters come from a texture.
    bool shades() const { return has(albedo) || has(roughness) || has(metallic) || has(emission); }
    // m's textured parameters replaced by the textures' values at uv.
    void apply(Material& m, Uv uv) const;
    // m as the integrator's strategies must see it anywhere on the surface: a textured roughness
    // glossy, a textured metallic mixed, a textured colour its scale.
    Material everywhere(Material m) const;
};

}  // namespace glint
