#include "render/strategies.h"

namespace glint {

namespace {

// Light tracing connects to a pinhole only; "on" with a lens is rejected by the loader.
CausticEmitter emitter_for(const Scene& scene) {
    const bool pinhole = !(scene.camera().aperture > 0);
    if (scene.integrator().light_tracing == LightTracing::off || !pinhole) return {};
    return CausticEmitter(scene);
}

}  // namespace

Strategies::Strategies(const Scene& scene) : caustic_emitter_(emitter_for(scene)) {
    if (caustic_emitter_.has_sphere_lights()) casters_ = CasterSampler(scene);
}

}  // namespace glint
