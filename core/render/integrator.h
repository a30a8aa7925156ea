// Unidirectional path tracing: each vertex's BSDF sampled for the bounce (scene/bsdf.h), next-event
// estimation at every non-specular vertex combined with BSDF sampling by the power heuristic,
// Russian roulette on the path throughput and a hard depth cap. The tracer never asks which
// material it hit, only its BSDF's flags.
//
// The tracer owns the strategies its estimator combines (strategies.h): with light tracing
// (light_tracer.h), each diffuse (Lambertian) vertex x is connected to the light path's diffuse
// vertices and the caustic paths it splats are left to it; where light tracing cannot reach,
// specular spheres are sampled as lights. Which strategy counts which path, and why the weights
// make an unbiased estimate, is mis.h's; found_light_weight() is where a bounce's share is taken.
#pragma once

#include "scene/camera.h"
#include "render/aov.h"
#include "render/guided_bsdf.h"
#include "render/light_tracer.h"
#include "render/path_guide.h"
#include "base/rng.h"
#include "render/sampler.h"
#include "render/strategies.h"
#include "scene/bsdf.h"
#include "scene/scene.h"

namespace glint {

// What the camera sees through specular vertices only: emitters, their images in mirrors and
// glass, the background. Where that varies across a pixel (the light's edge) it is estimated
// apart from the rest of the path, from more camera rays (see direct_view.h).
enum class DirectView {
    gathered,  // the path gathers it with everything else
    left_out,  // the path gathers only what it finds after its first non-specular vertex
    alone      // the path gathers only it, and ends at its first non-specular vertex
};

// What the strategies make of a vertex, from its BSDF's flags: specular (every lobe a delta: no
// light sampling), diffuse (Lambertian alone: light paths, their connections and the
// CasterSampler work there, mis.h), or glossy (anything else non-specular: light sampling and
// BSDF sampling only).
enum class VertexKind { specular, diffuse, glossy };

inline VertexKind vertex_kind(BsdfFlags flags) {
    return flags.is_specular() ? VertexKind::specular : flags.is_diffuse() ? VertexKind::diffuse : VertexKind::glossy;
}

// The shape of a camera path so far, for handing caustic paths to light tracing. caustic: one
// diffuse vertex, then specular+; glossy_caustic: one glossy vertex, then specular+.
enum class PathShape { camera, diffuse, caustic, glossy, glossy_caustic, other };

class PathTracer {
public:
    PathTracer(const Scene& scene, const Camera& camera) : scene_(scene), camera_(camera), strategies_(scene) {}

    const Strategies& strategies() const { return strategies_; }
    // The guide whose learned distributions draw the bounces at non-specular vertices
    // (guided_bsdf.h); nullptr: the BSDF alone draws them.
    void set_guide(const PathGuide* guide) {
        guide_ = guide;
        guide_mixture_ = guide ? guide->config().mixture : 0;
    }

    // Radiance arriving along the camera ray, estimated with random numbers from rng; `light`
    // is this sample's light path (empty when the scene has no light tracing); `first`, if
    // given, the numbers the path's first non-specular vertex uses instead of rng's; `direct` how
    // the path treats what the camera sees through specular vertices only; `aov`, if given,
    // receives the path's features (aov.h; where glass splits the path, the refracted branch's);
    // `training`, if given, the radiance the path brings back to each of its guided bounces.
    Rgb radiance(Ray ray, Rng& rng, const LightPath& light = kNoLightPath, const FirstVertexSamples* first = nullptr,
                 DirectView direct = DirectView::gathered, Aov* aov = nullptr, PathGuide* training = nullptr) const;

private:
    // Where a path is: its next ray, what it carries, the vertex it leaves and how it got there.
    struct PathState {
        Ray ray;
        Rgb throughput{1};
        int depth = 0;
        uint32_t self = kNoPrimitive;
        PathShape shape = PathShape::camera;
        bool specular = true;  // the camera "samples" its ray like a specular bounce: no MIS
        VertexKind previous_kind = VertexKind::specular;
        double bsdf_pdf = 0;
        Vec3 previous_point, previous_facing;
        // The path's last diffuse vertices as a light path could have made them: v, then
        // specular+ and diffuse vertices alternating, `chain` diffuse vertices in all (0: none,
        // because v's predecessor is specular), and the density (over π) with which v's
        // predecessor, the eye or a diffuse vertex, reaches v. A light path's vertex at v is
        // weighed against that.
        int chain = 0;
        double chain_density = 0;
        const FirstVertexSamples* first = nullptr;  // until the first non-specular vertex has used them
        // Since a diffuse vertex light tracing cannot reach (chain 0): the densities with which
        // its bounce and the CasterSampler pick the direction the path left it by (caster_pdf 0
        // where it does not apply), and the specular vertices met since.
        double caster_pdf = 0, caster_bsdf_pdf = 0;
        int caster_bounces = 0;
        DirectView direct_view = DirectView::gathered;
        PathGuide* training = nullptr;
        bool seen_directly = true;  // no non-specular vertex yet: what the path finds belongs to the direct view
        // Whether light found now counts: the direct view's share depends on the path's part.
        bool counts_found_light() const { return !(seen_directly && direct_view == DirectView::left_out); }
    };
    // Glass met in the first kSplitDepth bounces is split: both the reflection and the
    // refraction are followed, each weighted by its Fresnel factor, where smallpt's random pick
    // makes the light's images in a glass ball speckle. Each level doubles the paths a camera
    // ray may branch into: 2 keeps them at four. The refraction carries on the path's AOVs: what
    // lies behind glass, one deterministic branch, as a denoiser wants the features it sees.
    static constexpr int kSplitDepth = 2;
    // `aov` (kept out of PathState, which glass splitting copies) is filled in until the first
    // non-specular vertex; nullptr: no AOVs.
    Rgb trace(PathState path, Rng& rng, const LightPath& light, Aov* aov = nullptr) const;
    // Fills in `aov` at a surface the path meets (hit at distance t along its ray); returns
    // nullptr at the first non-specular vertex, where the AOVs are complete, and `aov` before it.
    Aov* note_aov(Aov* aov, const PathState& path, double t, const SurfaceInteraction& si, const Bsdf& bsdf,
                  bool specular) const;
    // Moves the path on from si along bs (false: it ends there, by Russian roulette or a black
    // throughput).
    bool extend_path(PathState& path, const SurfaceInteraction& si, VertexKind kind, const BsdfSample& bs,
                     Rng& rng) const;
    // Both next strategies end in a shadow ray, and most of their contributions are small: one
    // worth less than kShadowRoulette (a tenth of white on the display) is tested only with
    // probability worth / kShadowRoulette and then counted 1/probability times, which keeps the
    // mean. It trades a little variance for the shadow rays it saves: a higher threshold saves
    // more and adds more.
    static constexpr double kShadowRoulette = 0.1;
    // Light arriving from one sampled light point at si (reached along d with throughput beta),
    // times f·cos, MIS-weighted against BSDF sampling.
    // (u1, u2) pick the point on the light.
    Rgb direct_light(const SurfaceInteraction& si, const Vec3& d, const GuidedBsdf& bsdf, const Rgb& beta, double u1,
                     double u2, Rng& rng) const;
    // Light reaching diffuse vertex x (reached along d with throughput beta) through a mirror
    // or glass sphere picked by the CasterSampler, times f·cos, MIS-weighted against
    // the bounce: the chain of specular vertices is followed as the path tracer would (Fresnel
    // picks at random), for at most kMaxCasterBounces vertices.
    Rgb through_caster(const SurfaceInteraction& x, const Vec3& d, const GuidedBsdf& bsdf, const Rgb& beta, Rng& rng) const;
    static constexpr int kMaxCasterBounces = 8;
    // What reaches the eye through diffuse vertex x (reached along d with throughput beta)
    // from light vertex y, MIS-weighted against the path tracer's bounces.
    Rgb connect(const SurfaceInteraction& x, const Vec3& d, const GuidedBsdf& bsdf, const Rgb& beta, const LightVertex& y,
                Rng& rng) const;
    // The weight of emission found through specular vertices after a diffuse vertex, against
    // the light path that could also have found it; `density_over_pi` belongs to that light
    // path's first diffuse vertex (0: no light path could).
    double bounce_weight(double density_over_pi, const Ray& ray, const SurfaceInteraction& si,
                         uint32_t last_specular) const;
    // The share of emission at si that the path's last bounce found, against whichever other
    // strategy could also have found it (mis.h): next-event estimation, a light path or the
    // CasterSampler; 1 where none could.
    double found_light_weight(const PathState& path, const SurfaceInteraction& si, bool nee) const;
    // What a path that leaves a scene with an environment or a sun finds: each weighed against
    // next-event estimation's sampling of it; the film's background where there is no
    // environment or it is hidden.
    Rgb escaped(const PathState& path, bool nee) const;
    // The emission of the surface `hit` along `ray`, textured or not.
    Rgb emission_at(const Ray& ray, const Hit& hit) const;
    // What non-specular vertex si gathers, added to `result` in turn: next-event estimation
    // (with `first`'s numbers, if given), and at a diffuse vertex the connections to the light
    // path's vertices and the light through casters; also notes where the path stands in a
    // light path's chain.
    void gather_at_vertex(PathState& path, const SurfaceInteraction& si, const GuidedBsdf& bsdf, VertexKind kind,
                          const FirstVertexSamples* first, const LightPath& light, bool nee, Rng& rng,
                          Rgb& result) const;

    const Scene& scene_;
    const Camera& camera_;
    Strategies strategies_;
    const PathGuide* guide_ = nullptr;
    double guide_mixture_ = 0;
};

}  // namespace glint
