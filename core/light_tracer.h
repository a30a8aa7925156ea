// Light tracing of caustic paths: from a light, through one or more specular bounces (the first
// on a specular sphere the CausticEmitter aims at), to a diffuse surface, which is connected to
// the eye and splatted onto the film with the pixel filter's weight. It estimates exactly the
// paths the path tracer leaves out (camera → diffuse → specular+ → light, see PathTracer), so
// the two add up to the image without double counting and without bias. Only caustics seen
// directly: continuing diffusely from the light side (caustics seen after more diffuse
// bounces) cost as much as the camera paths on smallpt's box and gained less than they cost.
#pragma once

#include "camera.h"
#include "film.h"
#include "filter.h"
#include "rng.h"
#include "scene.h"

namespace glint {

class LightTracer {
public:
    LightTracer(const Scene& scene, const Camera& camera, Filter filter, Film& film)
        : scene_(scene), camera_(camera), filter_(filter), film_(film) {}

    // One light path; every contribution goes to the film as a splat. Thread-safe.
    void trace(Rng& rng) const;

private:
    // Connects diffuse vertex si, reached along direction d_in with throughput beta, to the eye.
    void splat(const SurfaceInteraction& si, const Vec3& d_in, const Material& m, const Rgb& beta) const;

    const Scene& scene_;
    const Camera& camera_;
    Filter filter_;
    Film& film_;
};

}  // namespace glint
