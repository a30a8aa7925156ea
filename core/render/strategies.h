// The sampling strategies the path tracer's estimator adds to its own bounces and next-event
// estimation (the scene's LightSet), built from the scene for each render: the scene stays
// data that any estimator can read, and the estimator owns what it samples with. How the
// strategies' weights make one unbiased estimate is mis.h's.
#pragma once

#include "render/caster_sampler.h"
#include "render/caustic_emitter.h"
#include "scene/scene.h"

namespace glint {

class Strategies {
public:
    explicit Strategies(const Scene& scene);

    // Whether light tracing takes the caustic paths, and where its paths start (empty if not).
    bool light_tracing() const { return !caustic_emitter_.empty(); }
    const CausticEmitter& caustic_emitter() const { return caustic_emitter_; }
    // With light tracing: the mirror and glass spheres, sampled from the diffuse points the
    // camera sees only through specular vertices (where light tracing cannot reach).
    const CasterSampler& casters() const { return casters_; }
    // Whether path guiding draws the bounces at non-specular vertices (path_guide.h).
    bool guiding() const { return guiding_; }

private:
    CausticEmitter caustic_emitter_;
    CasterSampler casters_;
    bool guiding_ = false;
};

}  // namespace glint
