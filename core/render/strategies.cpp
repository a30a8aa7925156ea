#include "render/strategies.h"

namespace glint {

namespace {

// Light tracing connects to a pinhole only; "on" with a lens is rejected by the loader.
CausticEmitter emitter_for(const Scene& scene) {
    const bool pinhole = !(scene.camera().aperture > 0);
    if (scene.integrator().light_tracing == LightTracing::off || !pinhole) return {};
    return CausticEmitter(scene);
}

bool guides(const Scene& scene) {
    switch (scene.integrator().guiding) {
        case Guiding::on: return true;
        case Guiding::off: return false;
        // Measured against guiding off on cornell_box, mesh and sponza, guiding reaches equal
        // error later on all three (docs/estimator.md): auto keeps it off until it wins.
        case Guiding::automatic: return false;
    }
    return false;
}

}  // namespace

Strategies::Strategies(const Scene& scene) : caustic_emitter_(emitter_for(scene)), guiding_(guides(scene)) {
    if (caustic_emitter_.has_sphere_lights()) casters_ = CasterSampler(scene);
}

}  // namespace glint
