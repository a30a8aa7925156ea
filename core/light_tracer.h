// Light tracing of caustic paths: from a light, through one or more specular bounces (the first
// on a specular sphere the CausticEmitter aims at), to a diffuse surface y; then one cosine
// bounce from y that meets a specular surface, through specular bounces to a diffuse surface z.
// Three strategies use these vertices, each the only one or the better one for some paths:
// - y is connected to the eye and splatted onto the film with the pixel filter's weight. That
//   estimates exactly the paths the path tracer leaves out (camera → y → specular+ → light, see
//   PathTracer), so the two add up to the image without double counting and without bias.
// - z is splatted the same way, weighted by the power heuristic against the path tracer, which
//   also finds camera → z → specular+ → y → specular+ → light when both bounces are lucky.
// - y and z are handed back as LightVertex, to which the path tracer connects each diffuse
//   vertex x of the camera path (bidirectional path tracing's connection strategy, restricted to
//   these light paths), again weighted against the path tracer's own bounces.
// On smallpt's box, before these connections, the paths through y carried 82% of the variance
// (those through z, specular-diffuse-specular, the larger part). Continuing diffusely from y
// to any surface (caustics seen after more diffuse bounces) cost as much as the camera paths
// and gained less than it cost: connections reach those paths from the camera side.
//
// With cosine sampling at every diffuse vertex, the two strategies' densities for a path differ
// only at its ends, whatever lies between (PathTracer::radiance): the light side's emission
// density against the camera side's density of reaching the light path's first diffuse vertex.
#pragma once

#include "camera.h"
#include "film.h"
#include "filter.h"
#include "rng.h"
#include "scene.h"

namespace glint {

// A diffuse vertex of a light path and what arrives there.
struct LightVertex {
    SurfaceInteraction si;
    Vec3 d_in;                 // the direction the light arrives along
    Rgb beta{0};               // emitted radiance · cos / pdf(emitted ray) · the path's BSDF weights
    Rgb albedo{0};
    double emitted_ratio = 0;  // cos at the light / pdf(emitted ray): what MIS needs of the light side
    int hits = 0;              // surface hits from the light to here, both counted
};

struct LightPath {
    LightVertex vertices[2];  // y, then z
    int size = 0;
};

class LightTracer {
public:
    LightTracer(const Scene& scene, const Camera& camera, Filter filter, Film& film)
        : scene_(scene), camera_(camera), filter_(filter), film_(film) {}

    // One light path: its connections to the eye go to the film as splats; its diffuse
    // vertices are returned for the camera path to connect to. Thread-safe.
    LightPath trace(Rng& rng) const;

    // The power heuristic's weight, against the path tracer, of a path whose first diffuse vertex
    // from the light side is reached from the camera side with area density `density` (divided
    // by π, the cosine sampling's density at that vertex) — the same ratio on both sides.
    static double light_side_weight(double density_over_pi, double emitted_ratio) {
        const double r = density_over_pi * emitted_ratio;
        return 1 / (1 + r * r);
    }

private:
    // Follows `ray` from primitive `self` through specular vertices to the first diffuse
    // surface; the first surface must be specular (from the light: one of the spheres the
    // emitter aims at, `light`'s targets). Counts hits and multiplies `throughput` on the way.
    bool to_diffuse(Ray ray, uint32_t self, uint32_t light, Rgb& throughput, int& hits, Rng& rng,
                    SurfaceInteraction& si, Vec3& d_in) const;
    // Connects vertex v to the eye, with weight w.
    void splat(const LightVertex& v, double w) const;

    const Scene& scene_;
    const Camera& camera_;
    Filter filter_;
    Film& film_;
};

}  // namespace glint
