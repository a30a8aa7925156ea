// How the path tracer's strategies share the paths they can all find, in one place: a path
// that k strategies can sample is counted by each with a weight, and the estimate is unbiased
// when the weights of every path sum to one (Veach 1997, multiple importance sampling). Every
// pair below is weighed by the power heuristic from the same two densities on both sides, so
// its weights are x²/(x² + y²) and y²/(y² + x²): they sum to one whichever the densities are.
//
// Emission found by a bounce from a non-specular vertex x, against:
// - next-event estimation at x (PathTracer::direct_light): power_heuristic(light pdf, BSDF pdf)
//   there, power_heuristic(BSDF pdf, light pdf) on the bounce, the BSDF pdf x's own, glossy or
//   diffuse;
// and from a diffuse (Lambertian) vertex x also against:
// - the CasterSampler at x, for light reaching x through one to kMaxCasterBounces specular
//   vertices from a diffuse vertex light tracing cannot reach (PathTracer::through_caster):
//   power_heuristic(caster pdf, BSDF pdf) there, power_heuristic(BSDF pdf, caster pdf) on the
//   bounce;
// - a light path's diffuse vertex v met by x's connection, or by the eye's splat when v is the
//   first diffuse vertex after the camera (light_tracer.h): light_side_weight() there,
//   1 - light_side_weight() on the bounce (PathTracer::bounce_weight), from the same ratio.
// These cases are disjoint: NEE's follows a non-specular bounce, the others specular ones; the
// CasterSampler's starts at a vertex no light path reaches (chain 0), the light path's at one
// it does.
//
// Two sets of paths are not shared but split, each left to one strategy with weight one:
// - camera → y → specular+ → light, with y the first diffuse vertex and its last specular
//   vertex a sphere the CausticEmitter aims at from that point of the light: light tracing's
//   splat of y alone; the path tracer drops what it finds there (PathTracer::trace); the same
//   with the sun for the light, its direction any of the disc's (PathTracer::escaped);
// - in the pixels where the direct view splits (direct_view.h), what the camera sees through
//   specular vertices only: the extra direct-view rays alone; the sample's own path leaves it out.
//
// The light-side weights below assume cosine sampling at every diffuse vertex. A glossy vertex
// (integrator.h's VertexKind) never takes part: light paths end at one, a camera path's chain
// starts again after one, and no connection or CasterSampler ray leaves one.
#pragma once

#include <cmath>

#include "base/math.h"
#include "base/sampling.h"

namespace glint {

// The power heuristic's weight, against the path tracer, of a path whose first diffuse vertex
// from the light side is reached from the camera side with area density `density` (divided by
// π, the cosine sampling's density at that vertex) — the same ratio on both sides. With cosine
// sampling at every diffuse vertex, the two strategies' densities differ only at the path's two
// ends, whatever lies between: the light side's emission density (cos / emitted_ratio) against
// the density with which x (or the eye) reaches v.
inline double light_side_weight(double density_over_pi, double emitted_ratio) {
    const double r = density_over_pi * emitted_ratio;
    return 1 / (1 + r * r);
}

// The two ends' densities of a connection x → y, cos_x·cos_y / (π·|x - y|²) / π: the density
// with which cosine sampling at x reaches y, over π.
inline double connection_density_over_pi(double cos_x, double cos_y, double distance2) {
    return std::fabs(cos_x * cos_y) / (kPi * kPi * distance2);
}

}  // namespace glint
