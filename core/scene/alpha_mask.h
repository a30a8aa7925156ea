// A cut-out: where a texture's alpha is below a cut-off, the surface is not there for any ray
// (glTF's alphaMode MASK, an MTL map_d). Geometry's queries skip the holes, so shadow rays, light
// paths and camera rays all pass through the same holes.
#pragma once

#include "scene/texture.h"
#include "shapes/triangle_attributes.h"

namespace glint {

struct AlphaMask {
    TextureLookup alpha;  // texture null: no mask
    double cutoff = 0.5;  // glTF's alphaCutoff default

    bool present() const { return alpha.texture != nullptr; }
    // Whether the surface is there at uv.
    bool keeps(Uv uv) const { return alpha.value(uv.u, uv.v) >= cutoff; }
};

}  // namespace glint
