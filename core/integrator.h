// Unidirectional path tracing: cosine-sampled diffuse bounces, next-event estimation at
// diffuse surfaces combined with BSDF sampling by the power heuristic, smallpt's mirror and
// glass, Russian roulette on the path throughput and a hard depth cap. When the scene has light
// tracing, the caustic paths it covers (camera → diffuse → specular+ → light) are left to it.
#pragma once

#include "rng.h"
#include "scene.h"

namespace glint {

class PathTracer {
public:
    explicit PathTracer(const Scene& scene) : scene_(scene) {}

    // Radiance arriving along the camera ray, estimated with random numbers from rng.
    Rgb radiance(Ray ray, Rng& rng) const;

private:
    // Light arriving from one sampled light point, times f·cos, MIS-weighted against BSDF sampling.
    Rgb direct_light(const SurfaceInteraction& si, const Vec3& d, const Material& m, Rng& rng) const;

    const Scene& scene_;
};

}  // namespace glint
