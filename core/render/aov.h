// What a camera path shows a denoiser at its first diffuse vertex: the features (arbitrary
// output variables) the film averages beside the image when RenderSettings::aovs asks for them.
// Specular vertices (mirror, glass) are passed through, so a mirror shows what it reflects and a
// glass ball what lies behind it, as the image does; see docs/aovs.md.
#pragma once

#include "base/math.h"

namespace glint {

struct Aov {
    // The material's albedo at the first diffuse vertex; 0 for a path that finds none (it
    // escapes to the background, or ends at a specular vertex by Russian roulette or the depth
    // cap). An emitter is a diffuse vertex and gives its albedo.
    Rgb albedo{0};
    // The unit normal there, in world space, turned to face the ray that arrived; 0 where there
    // is no diffuse vertex.
    Vec3 normal{0};
    // The distance from the eye to the first surface the camera ray meets, of any material
    // (a mirror's own distance, not its reflection's); 0 for a ray that meets nothing, so that
    // no infinity reaches a file.
    double depth = 0;
};

}  // namespace glint
