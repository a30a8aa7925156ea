// Light tracing of caustic paths. A light path leaves a light toward a specular sphere the
// CausticEmitter aims at, follows specular bounces to a diffuse surface (its vertex y), and
// from there repeats: one cosine bounce that meets a specular surface, specular bounces, the
// next diffuse vertex — up to kLightVertices of them, each separated from the last by
// specular vertices only (a bounce that meets a diffuse surface ends the path: paths through
// two diffuse vertices in a row are the connections' and the path tracer's). Its strategies:
// - y is connected to the eye and splatted onto the film with the pixel filter's weight. That
//   estimates exactly the paths the path tracer leaves out (camera → y → specular+ → light), so
//   the two add up to the image without double counting and without bias (mis.h).
// - every later vertex is splatted the same way, weighted by the power heuristic against the
//   path tracer, which also finds camera → z → specular+ → y → specular+ → light when all its
//   bounces are lucky;
// - the vertices are handed back as a LightPath, to whose vertices the path tracer connects each
//   diffuse vertex x of the camera path (bidirectional path tracing's connection strategy,
//   restricted to these light paths), again weighted against the path tracer's own bounces.
// Without the connections, such paths carry most of the variance of smallpt's box, through
// specular-diffuse-specular chains (the balls seen from the walls lit through the balls), which
// the path tracer alone finds only by chance. Light paths stop at the first diffuse bounce
// that meets a diffuse surface: going on to any surface (caustics seen after more diffuse
// bounces) would cost as much as the camera paths, and connections reach those paths from the
// camera side.
//
// A path x → v → (specular+ → diffuse)* → specular+ → light has exactly two strategies: the
// path tracer's bounces, and the light path's vertex v met from x (a connection) or from the
// eye (a splat); light_side_weight() (mis.h) weighs them.
#pragma once

#include "scene/camera.h"
#include "render/film.h"
#include "render/settings.h"
#include "render/filter.h"
#include "base/rng.h"
#include "render/strategies.h"
#include "scene/scene.h"

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

inline constexpr int kLightVertices = 4;

struct LightPath {
    LightVertex vertices[kLightVertices];  // from the light: y, then the later ones
    int size = 0;
};
// For camera paths without one: shared, since building an empty path writes ~600 bytes.
inline const LightPath kNoLightPath{};

class LightTracer {
public:
    // `strategies`: the path tracer's, whose CausticEmitter starts the light paths. The image
    // is width × height pixels; `film` holds its pixels in `window` (splats elsewhere are left out).
    LightTracer(const Scene& scene, const Strategies& strategies, const Camera& camera, Filter filter, int width,
                int height, const Region& window, Film& film)
        : scene_(scene), strategies_(strategies), camera_(camera), filter_(filter), width_(width), height_(height),
          window_(window), film_(film) {}

    // One light path: its connections to the eye go to the film as splats; its diffuse
    // vertices are returned for the camera path to connect to. Thread-safe.
    LightPath trace(Rng& rng) const;

private:
    // Follows `ray` from primitive `self` through specular vertices to the first diffuse
    // surface (or, with `glossy_ends`, the first that is not specular); the first surface must
    // be specular (from the light: one of the spheres the emitter aims at, `light`'s targets).
    // Counts hits and multiplies `throughput` on the way.
    bool to_diffuse(Ray ray, uint32_t self, uint32_t light, Rgb& throughput, int& hits, Rng& rng,
                    SurfaceInteraction& si, Vec3& d_in, bool glossy_ends = false) const;
    void sun_caustic(const EmittedRay& e, Rng& rng) const;
    // Connects vertex v to the eye, with weight w: through its albedo/π, or where `glossy` is
    // its material, through that material's BSDF toward the eye.
    void splat(const LightVertex& v, double w, const Material* glossy = nullptr) const;

    const Scene& scene_;
    const Strategies& strategies_;
    const Camera& camera_;
    Filter filter_;
    int width_, height_;
    Region window_;
    Film& film_;
};

}  // namespace glint
