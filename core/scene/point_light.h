// Point and spot lights as glTF's KHR_lights_punctual defines them, so that a glTF file's map
// one to one: a point of radiant intensity I (W/sr) in every direction, or, for a spot, along
// `direction` within `outer` of it, full to `inner` and fading between as the extension's
// reference does: a factor clamp((cos θ − cos outer) / (cos inner − cos outer), 0, 1)².
// Delta lights: only light sampling reaches them.
#pragma once

#include <algorithm>
#include <cmath>

#include "base/math.h"

namespace glint {

struct PointLight {
    Vec3 position;
    Rgb intensity{1};  // W/sr
    bool spot = false;
    Vec3 direction{0, -1, 0};  // a spot's axis, unit, the way it shines
    double cos_inner = 1, cos_outer = std::cos(kPi / 4);  // glTF's defaults: 0 and π/4

    // The intensity toward unit direction w (from the light).
    Rgb intensity_toward(const Vec3& w) const {
        if (!spot) return intensity;
        const double scale = 1 / std::max(1e-3, cos_inner - cos_outer);
        const double t = std::clamp((dot(direction, w) - cos_outer) * scale, 0.0, 1.0);
        return intensity * (t * t);
    }
    // The weight light selection gives it beside emitters (area × radiance, power over 2π):
    // its power within its cone, 2π(1 − cos outer)·I for a spot (an upper bound), 4π·I else.
    double selection_weight() const {
        const double solid_angle = spot ? 2 * kPi * (1 - cos_outer) : 4 * kPi;
        return solid_angle * luminance(intensity) / (2 * kPi);
    }
};

}  // namespace glint
