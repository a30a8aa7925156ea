#include "render/integrator.h"

#include "base/sampling.h"
#include "render/mis.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <optional>
#include <utility>

namespace glint {
namespace {

PathShape extend(PathShape shape, VertexKind kind) {
    const bool specular = kind == VertexKind::specular;
    switch (shape) {
        case PathShape::camera:
            return specular ? PathShape::other : kind == VertexKind::diffuse ? PathShape::diffuse : PathShape::glossy;
        case PathShape::diffuse:
        case PathShape::caustic: return specular ? PathShape::caustic : PathShape::other;
        case PathShape::glossy:
        case PathShape::glossy_caustic: return specular ? PathShape::glossy_caustic : PathShape::other;
        case PathShape::other: return PathShape::other;
    }
    return PathShape::other;
}

// Whether y's own sphere hides x: light reached y from inside the sphere and x is outside it.
// (Elsewhere a segment from y to a point on the side the light came from stays off y's
// surface, so the shadow ray may skip y's primitive, as it must: rounding could find y itself.)
bool hidden_by_own_sphere(const Geometry& geometry, const LightVertex& y, const Vec3& x) {
    if (!geometry.is_sphere(y.si.prim) || dot(y.d_in, y.si.n) <= 0) return false;
    const Sphere& s = geometry.sphere(y.si.prim);
    const Vec3 from_centre = x - s.centre;
    return dot(from_centre, from_centre) > s.radius * s.radius;
}

// Russian roulette on a contribution before its shadow ray (PathTracer::kShadowRoulette).
bool survives_roulette(Rgb& value, double threshold, Rng& rng) {
    const double worth = max_component(value);
    if (!(worth > 0)) return false;
    if (worth >= threshold) return true;
    if (rng.uniform() * threshold >= worth) return false;
    value *= threshold / worth;
    return true;
}

// The bounces of a path that trains the guide, each told at the end the radiance the path
// brought back along it: what the path gathered after it, over the path's throughput there.
class TrainingRecords {
public:
    explicit TrainingRecords(PathGuide* guide) : guide_(guide) {
        if (guide) records_.emplace();
    }

    void add(const Vec3& p, const BsdfSample& bs, const Rgb& throughput, const Rgb& gathered) {
        if (!guide_ || bs.is_specular() || !(bs.pdf > 0) || count_ == kMaxRecords) return;
        (*records_)[count_++] = {p, bs.wi, bs.pdf, throughput, gathered};
    }
    void finish(const Rgb& gathered) const {
        for (int i = 0; i < count_; ++i) {
            const Record& r = (*records_)[i];
            const Rgb since = gathered - r.gathered;
            const Rgb radiance{share(since.x, r.throughput.x), share(since.y, r.throughput.y),
                               share(since.z, r.throughput.z)};
            const double amount = luminance(radiance) / r.pdf;
            if (std::isfinite(amount)) guide_->record(r.p, r.wi, std::max(amount, 0.0));
        }
    }

private:
    static double share(double value, double throughput) { return throughput > 0 ? value / throughput : 0; }
    // Deeper bounces carry little and are not recorded.
    static constexpr int kMaxRecords = 16;
    struct Record {
        Vec3 p, wi;
        double pdf;
        Rgb throughput, gathered;
    };
    PathGuide* guide_;
    int count_ = 0;
    // Made only for a training path: every other path would zero them at each trace().
    std::optional<std::array<Record, kMaxRecords>> records_;
};

}  // namespace

Rgb PathTracer::direct_light(const SurfaceInteraction& si, const Vec3& d, const GuidedBsdf& bsdf, const Rgb& beta,
                             double u1, double u2, Rng& rng) const {
    LightSample ls;
    const Vec3 facing = dot(d, si.n) < 0 ? si.n : -si.n;
    if (!scene_.lights().sample(si.p, si.prim, u1, u2, ls, facing)) return Rgb{0};
    if (scene_.has_textured_lights() && ls.prim != kNoPrimitive && scene_.material(ls.prim).maps != Material::kNoMaps)
        ls.emission = scene_.emission_at(si.p, ls);
    const BsdfValue f = bsdf.evaluate(-d, ls.wi);
    Rgb value = beta * f.f_cos * ls.emission * ((ls.delta ? 1 : power_heuristic(ls.pdf, f.pdf)) / ls.pdf);
    if (!survives_roulette(value, kShadowRoulette, rng)) return Rgb{0};
    Ray shadow = spawn_ray(si, ls.wi);
    shadow.tmax = ls.distance;
    if (scene_.geometry().occluded(shadow, si.prim, ls.prim)) return Rgb{0};
    return value;
}

Rgb PathTracer::connect(const SurfaceInteraction& x, const Vec3& d, const GuidedBsdf& bsdf, const Rgb& beta,
                        const LightVertex& y, Rng& rng) const {
    const Vec3 to_y = y.si.p - x.p;
    const double distance2 = dot(to_y, to_y);
    if (!(distance2 > 0)) return Rgb{0};
    const Vec3 w = to_y / std::sqrt(distance2);
    const double cos_x = dot(w, x.n), cos_y = dot(w, y.si.n);
    // Reflection only: y must lie on the side x was reached from, x on the side light reached y from.
    if (cos_x * dot(d, x.n) >= 0 || cos_y * dot(y.d_in, y.si.n) <= 0) return Rgb{0};
    if (hidden_by_own_sphere(scene_.geometry(), y, x.p)) return Rgb{0};
    const double density_over_pi = connection_density_over_pi(cos_x, cos_y, distance2);
    // Both ends Lambertian: f_x · G · f_y = albedo_x · albedo_y · cos_x·cos_y / (π²·distance²).
    Rgb value = beta * bsdf.albedo() * y.albedo * y.beta *
                (density_over_pi * light_side_weight(density_over_pi, y.emitted_ratio));
    if (!survives_roulette(value, kShadowRoulette, rng)) return Rgb{0};
    const Vec3 from = offset_ray_origin(x, w), to = offset_ray_origin(y.si, -w);
    Ray shadow{from, normalize(to - from)};
    shadow.tmax = length(to - from);
    if (scene_.geometry().occluded(shadow, x.prim, y.si.prim)) return Rgb{0};
    return value;
}

Rgb PathTracer::through_caster(const SurfaceInteraction& x, const Vec3& d, const GuidedBsdf& bsdf, const Rgb& beta,
                               Rng& rng) const {
    const double u_pick = rng.uniform(), u1 = rng.uniform(), u2 = rng.uniform();
    Vec3 wi;
    double pdf;
    if (!strategies_.casters().sample(x.p, u_pick, u1, u2, wi, pdf)) return Rgb{0};
    const BsdfValue f = bsdf.evaluate(-d, wi);
    if (is_black(f.f_cos)) return Rgb{0};
    Rgb throughput = beta * f.f_cos * (power_heuristic(pdf, f.pdf) / pdf);
    Rgb result{0};
    Ray ray = spawn_ray(x, wi);
    uint32_t self = x.prim;
    for (int bounces = 0;; ++bounces) {  // specular vertices behind the ray
        Hit hit;
        if (!scene_.geometry().intersect(ray, self, hit)) break;
        const SurfaceInteraction si = scene_.interaction(ray, hit);
        Material scratch;
        const Material& hm = scene_.material_at(si, scratch);
        if (bounces > 0) result += throughput * hm.emission;  // at 0 it is light sampling's
        if (!scene_.flags(hit.prim).is_specular() || bounces == kMaxCasterBounces) break;
        const BsdfSample bs = Bsdf(hm, si, -ray.d).sample(-ray.d, rng);
        throughput *= bs.weight;
        if (is_black(throughput)) break;
        ray = spawn_ray(si, bs.wi);
        self = hit.prim;
    }
    return result;
}

double PathTracer::bounce_weight(double density_over_pi, const Ray& ray, const SurfaceInteraction& si,
                                 uint32_t last_specular) const {
    if (!(density_over_pi > 0)) return 1;
    const CausticEmitter& emitter = strategies_.caustic_emitter();
    const Vec3 d_out = -ray.d;
    const double cos_out = dot(d_out, si.n);
    if (!(cos_out > 0) || !emitter.covers(si.prim, si.p, last_specular)) return 1;
    const double pdf = emitter.pdf(si.prim, si.p, d_out);
    if (!(pdf > 0)) return 1;
    return 1 - light_side_weight(density_over_pi, cos_out / pdf);
}

Rgb PathTracer::emission_at(const Ray& ray, const Hit& hit) const {
    const Material& m = scene_.material(hit.prim);
    if (m.maps == Material::kNoMaps) return m.emission;
    Material scratch;
    return scene_.material_at(scene_.geometry().interaction(ray, hit), scratch).emission;
}

Rgb PathTracer::radiance(Ray ray, Rng& rng, const LightPath& light, const FirstVertexSamples* first,
                         DirectView direct, Aov* aov, PathGuide* training) const {
    PathState path;
    path.ray = ray;
    path.first = first;
    path.direct_view = direct;
    path.training = training;
    if (aov) *aov = Aov{};
    return trace(path, rng, light, aov);
}

Aov* PathTracer::note_aov(Aov* aov, const PathState& path, double t, const SurfaceInteraction& si,
                          const Bsdf& bsdf, bool specular) const {
    if (path.depth == 0) aov->depth = camera_.near() + t;
    if (specular) return aov;
    aov->albedo = bsdf.albedo();
    aov->normal = dot(path.ray.d, si.n) < 0 ? si.n : -si.n;
    return nullptr;
}

bool PathTracer::extend_path(PathState& path, const SurfaceInteraction& si, VertexKind kind, const BsdfSample& bs,
                             Rng& rng) const {
    path.throughput *= bs.weight;
    if (is_black(path.throughput)) return false;
    if (path.depth >= scene_.integrator().rr_depth) {
        const double survive = std::min(1.0, max_component(path.throughput));
        if (rng.uniform() >= survive) return false;
        path.throughput *= 1 / survive;
    }
    const bool non_specular = kind != VertexKind::specular;
    if (non_specular) {
        path.caster_pdf = !strategies_.casters().empty() && path.chain == 0 && kind == VertexKind::diffuse
                              ? strategies_.casters().pdf(si.p, bs.wi)
                              : 0;
        path.caster_bsdf_pdf = bs.pdf;
        path.caster_bounces = 0;
    } else {
        ++path.caster_bounces;
    }
    path.shape = extend(path.shape, kind);
    path.seen_directly = path.seen_directly && !non_specular;
    path.specular = bs.is_specular();
    path.previous_kind = kind;
    path.bsdf_pdf = bs.pdf;
    path.previous_point = si.p;
    path.previous_facing = dot(path.ray.d, si.n) < 0 ? si.n : -si.n;
    path.self = si.prim;
    path.ray = spawn_ray(si, bs.wi);
    ++path.depth;
    return true;
}

// Light tracing and the caster sampler start no path at the environment or the sun: next-event
// estimation is the only other way to each.
Rgb PathTracer::escaped(const PathState& path, bool nee) const {
    const Vec3& d = path.ray.d;
    const bool mis = nee && !path.specular;
    const LightSet& lights = scene_.lights();
    const Environment* environment = scene_.environment();
    Rgb result = scene_.background();
    if (environment && (environment->settings().visible || !path.seen_directly))
        result = environment->radiance(d) * (mis ? power_heuristic(path.bsdf_pdf, lights.environment_pdf(d)) : 1);
    const Sun* sun = scene_.sun();
    if (!sun || !(sun->pdf(d) > 0)) return result;
    // Sun caustics that light tracing covers are its alone (mis.h).
    const bool traced_from_sun = strategies_.light_tracing() &&
                                 (path.shape == PathShape::caustic || path.shape == PathShape::glossy_caustic) &&
                                 strategies_.caustic_emitter().covers_sun(path.self);
    if (!traced_from_sun)
        result += sun->radiance(d) * (mis ? power_heuristic(path.bsdf_pdf, lights.sun_pdf(d)) : 1);
    return result;
}

double PathTracer::found_light_weight(const PathState& path, const SurfaceInteraction& si, bool nee) const {
    if (nee && !path.specular)
        return power_heuristic(path.bsdf_pdf,
                               scene_.lights().pdf(path.previous_point, path.self, si, path.previous_facing));
    if (strategies_.light_tracing() && path.specular && path.chain > 0 && path.chain <= kLightVertices)
        return bounce_weight(path.chain_density, path.ray, si, path.self);
    if (path.caster_pdf > 0 && path.caster_bounces >= 1 && path.caster_bounces <= kMaxCasterBounces)
        return power_heuristic(path.caster_bsdf_pdf, path.caster_pdf);
    return 1;
}

void PathTracer::gather_at_vertex(PathState& path, const SurfaceInteraction& si, const GuidedBsdf& bsdf, VertexKind kind,
                                  const FirstVertexSamples* first, const LightPath& light, bool nee, Rng& rng,
                                  Rgb& result) const {
    const Ray& ray = path.ray;
    const int max_depth = scene_.integrator().max_depth;
    if (nee) {
        const double u1 = first ? first->light[0] : rng.uniform(), u2 = first ? first->light[1] : rng.uniform();
        result += direct_light(si, ray.d, bsdf, path.throughput, u1, u2, rng);
    }
    if (kind == VertexKind::glossy) {  // no light path reaches or leaves a glossy vertex
        path.chain = 0;
        return;
    }
    for (int i = 0; i < light.size; ++i)
        if (path.depth + 1 + light.vertices[i].hits <= max_depth)
            result += connect(si, ray.d, bsdf, path.throughput, light.vertices[i], rng);
    if (!strategies_.light_tracing()) return;
    const bool after_diffuse = path.previous_kind == VertexKind::diffuse;
    if (path.depth == 0) {
        path.chain_density = camera_.area_density(si.p, si.n) / kPi;
    } else if (after_diffuse) {
        const Vec3 from_previous = si.p - path.previous_point;
        path.chain_density = connection_density_over_pi(dot(ray.d, path.previous_facing), dot(ray.d, si.n),
                                                        dot(from_previous, from_previous));
    }
    const bool after_specular = path.previous_kind == VertexKind::specular;
    path.chain = path.depth == 0 || after_diffuse ? 1 : after_specular && path.chain > 0 ? path.chain + 1 : 0;
    if (path.chain == 0 && !strategies_.casters().empty())
        result += through_caster(si, ray.d, bsdf, path.throughput, rng);
}

Rgb PathTracer::trace(PathState path, Rng& rng, const LightPath& light, Aov* aov) const {
    const IntegratorSettings& settings = scene_.integrator();
    const bool nee = settings.light_sampling && !scene_.lights().empty();
    Rgb result{0};
    TrainingRecords records(path.training);
    Material scratch;  // the material at a textured surface's point
    for (;;) {
        const Ray& ray = path.ray;
        Hit hit;
        if (!scene_.geometry().intersect(ray, path.self, hit)) {
            if (path.counts_found_light())
                result += path.throughput * (scene_.has_distant_lights() ? escaped(path, nee) : scene_.background());
            break;
        }
        const BsdfFlags flags = scene_.flags(hit.prim);
        const VertexKind kind = vertex_kind(flags);
        const bool specular = kind == VertexKind::specular;
        if (!specular && path.direct_view == DirectView::alone) {  // the direct view ends here
            if (scene_.material(hit.prim).is_emissive()) result += path.throughput * emission_at(ray, hit);
            break;
        }
        const SurfaceInteraction si = scene_.interaction(ray, hit);
        const Material& m = scene_.material_at(si, scratch);
        const Bsdf bsdf(m, si, -ray.d);
        const GuidedBsdf vertex(bsdf, specular || !guide_ ? nullptr : guide_->at(si.p), guide_mixture_);
        if (aov) aov = note_aov(aov, path, hit.t, si, bsdf, specular);
        // Caustic paths that light tracing covers are its alone (mis.h).
        const bool traced_from_light = strategies_.light_tracing() && path.shape == PathShape::caustic &&
                                       strategies_.caustic_emitter().covers(hit.prim, si.p, path.self);
        if (m.is_emissive() && !traced_from_light && path.counts_found_light())
            result += path.throughput * m.emission * found_light_weight(path, si, nee);
        if (path.depth + 1 >= settings.max_depth) break;
        const FirstVertexSamples* first = specular ? nullptr : std::exchange(path.first, nullptr);
        if (!specular) gather_at_vertex(path, si, vertex, kind, first, light, nee, rng, result);
        BsdfSample bs, reflected;
        if (specular && path.depth < kSplitDepth && flags.has(BsdfFlags::transmission) &&
            bsdf.split(-ray.d, reflected, bs)) {
            PathState branch = path;  // with the same stratified numbers for its first diffuse vertex
            if (extend_path(branch, si, kind, reflected, rng)) result += trace(branch, rng, light);
        } else {
            bs = vertex.sample(-ray.d, rng, first ? first->bounce : nullptr);
        }
        if (!extend_path(path, si, kind, bs, rng)) break;
        if (!specular) records.add(si.p, bs, path.throughput, result);
    }
    records.finish(result);
    return result;
}

}  // namespace glint
