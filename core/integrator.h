// Unidirectional path tracing: cosine-sampled diffuse bounces, next-event estimation at
// diffuse surfaces combined with BSDF sampling by the power heuristic, smallpt's mirror and
// glass, Russian roulette on the path throughput and a hard depth cap.
//
// When the scene has light tracing (light_tracer.h), its strategies share the work:
// - the caustic paths it splats from its first diffuse vertex y (camera → y → specular+ →
//   light) are left to it;
// - each diffuse vertex x is connected to the light path's diffuse vertices, and the paths
//   that both a connection (or a splat of z) and the path tracer's own bounces can find are
//   weighted between the two by the power heuristic.
#pragma once

#include "camera.h"
#include "light_tracer.h"
#include "rng.h"
#include "scene.h"

namespace glint {

class PathTracer {
public:
    PathTracer(const Scene& scene, const Camera& camera) : scene_(scene), camera_(camera) {}

    // Radiance arriving along the camera ray, estimated with random numbers from rng; `light`
    // is this sample's light path (empty when the scene has no light tracing).
    Rgb radiance(Ray ray, Rng& rng, const LightPath& light = {}) const;

private:
    // Both next strategies end in a shadow ray, and most of their contributions are small: one
    // worth less than kShadowRoulette (a tenth of white on the display) is tested only with
    // probability worth / kShadowRoulette and then counted 1/probability times, which keeps the
    // mean. On smallpt's box this cut 16% of the instructions for 1% more variance.
    static constexpr double kShadowRoulette = 0.1;
    // Light arriving from one sampled light point at si (reached along d with throughput beta),
    // times f·cos, MIS-weighted against BSDF sampling.
    Rgb direct_light(const SurfaceInteraction& si, const Vec3& d, const Material& m, const Rgb& beta, Rng& rng) const;
    // What reaches the eye through diffuse vertex x (reached along d with throughput beta)
    // from light vertex y, MIS-weighted against the path tracer's bounces.
    Rgb connect(const SurfaceInteraction& x, const Vec3& d, const Material& m, const Rgb& beta, const LightVertex& y,
                Rng& rng) const;
    // The weight of emission found through specular vertices after a diffuse vertex, against
    // the light path that could also have found it; `density_over_pi` belongs to that light
    // path's first diffuse vertex (0: no light path could).
    double bounce_weight(double density_over_pi, const Ray& ray, const SurfaceInteraction& si,
                         uint32_t last_specular) const;

    const Scene& scene_;
    const Camera& camera_;
};

}  // namespace glint
