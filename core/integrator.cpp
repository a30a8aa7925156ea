#include "integrator.h"

#include "sampling.h"

namespace glint {
namespace {

// The shape of the path so far, for handing caustic paths to light tracing.
enum class Shape { camera, diffuse, caustic, other };  // caustic: one diffuse, then specular+

Shape extend(Shape shape, bool diffuse) {
    switch (shape) {
        case Shape::camera: return diffuse ? Shape::diffuse : Shape::other;
        case Shape::diffuse: return diffuse ? Shape::other : Shape::caustic;
        case Shape::caustic: return diffuse ? Shape::other : Shape::caustic;
        case Shape::other: return Shape::other;
    }
    return Shape::other;
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

// The two ends' densities of a connection x → y, cos_x·cos_y / (π·|x - y|²) / π: the density
// with which cosine sampling at x reaches y, over π.
double connection_density_over_pi(double cos_x, double cos_y, double distance2) {
    return std::fabs(cos_x * cos_y) / (kPi * kPi * distance2);
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

}  // namespace

Rgb PathTracer::direct_light(const SurfaceInteraction& si, const Vec3& d, const Material& m, const Rgb& beta,
                             Rng& rng) const {
    const double u_pick = rng.uniform(), u1 = rng.uniform(), u2 = rng.uniform();
    LightSample ls;
    const Vec3 facing = dot(d, si.n) < 0 ? si.n : -si.n;
    if (!scene_.lights().sample(si.p, si.prim, u_pick, u1, u2, ls, facing)) return Rgb{0};
    double bsdf_pdf;
    const Rgb f_cos = diffuse_f_cos(m, d, si.n, ls.wi, bsdf_pdf);
    Rgb value = beta * f_cos * ls.emission * (power_heuristic(ls.pdf, bsdf_pdf) / ls.pdf);
    if (!survives_roulette(value, kShadowRoulette, rng)) return Rgb{0};
    Ray shadow = spawn_ray(si, ls.wi);
    shadow.tmax = ls.distance;
    if (scene_.geometry().occluded(shadow, si.prim, ls.prim)) return Rgb{0};
    return value;
}

Rgb PathTracer::connect(const SurfaceInteraction& x, const Vec3& d, const Material& m, const Rgb& beta,
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
    // f_x · G · f_y = albedo_x · albedo_y · cos_x·cos_y / (π²·distance²).
    Rgb value = beta * m.albedo * y.albedo * y.beta *
                (density_over_pi * LightTracer::light_side_weight(density_over_pi, y.emitted_ratio));
    if (!survives_roulette(value, kShadowRoulette, rng)) return Rgb{0};
    const Vec3 from = offset_ray_origin(x, w), to = offset_ray_origin(y.si, -w);
    Ray shadow{from, normalize(to - from)};
    shadow.tmax = length(to - from);
    if (scene_.geometry().occluded(shadow, x.prim, y.si.prim)) return Rgb{0};
    return value;
}

double PathTracer::bounce_weight(double density_over_pi, const Ray& ray, const SurfaceInteraction& si,
                                 uint32_t last_specular) const {
    if (!(density_over_pi > 0)) return 1;
    const CausticEmitter& emitter = scene_.caustic_emitter();
    const Vec3 d_out = -ray.d;
    const double cos_out = dot(d_out, si.n);
    if (!(cos_out > 0) || !emitter.covers(si.prim, si.p, last_specular)) return 1;
    const double pdf = emitter.pdf(si.prim, si.p, d_out);
    if (!(pdf > 0)) return 1;
    return 1 - LightTracer::light_side_weight(density_over_pi, cos_out / pdf);
}

Rgb PathTracer::radiance(Ray ray, Rng& rng, const LightPath& light) const {
    const IntegratorSettings& settings = scene_.integrator();
    const bool nee = settings.light_sampling && !scene_.lights().empty();
    const bool light_tracing = scene_.light_tracing();
    Shape shape = Shape::camera;
    Rgb result{0}, throughput{1};
    uint32_t self = kNoPrimitive;
    bool specular = true;  // the camera "samples" its ray like a specular bounce: no MIS
    bool previous_diffuse = false;
    double bsdf_pdf = 0;
    Vec3 previous, previous_facing;
    // The path's last diffuse vertices as a light path could have made them: v, then specular+
    // and diffuse vertices alternating, `chain` diffuse vertices in all (0: none, because v's
    // predecessor is specular), and the density (over π) with which v's predecessor, the eye
    // or a diffuse vertex, reaches v. A light path's vertex at v is weighed against that.
    int chain = 0;
    double chain_density = 0;
    for (int depth = 0;; ++depth) {
        Hit hit;
        if (!scene_.geometry().intersect(ray, self, hit)) {
            result += throughput * scene_.background();
            break;
        }
        const SurfaceInteraction si = scene_.geometry().interaction(ray, hit);
        const Material& m = scene_.material(hit.prim);
        const bool diffuse = m.type == MaterialType::diffuse;
        const bool traced_from_light = light_tracing && shape == Shape::caustic &&
                                       scene_.caustic_emitter().covers(hit.prim, si.p, self);
        if (m.is_emissive() && !traced_from_light) {
            // Emission found by BSDF sampling; where NEE or a light path could also have
            // found it, MIS-weight it.
            double w = 1;
            if (nee && !specular)
                w = power_heuristic(bsdf_pdf, scene_.lights().pdf(previous, self, si, previous_facing));
            else if (light_tracing && specular && chain > 0 && chain <= kLightVertices)
                w = bounce_weight(chain_density, ray, si, self);
            result += throughput * m.emission * w;
        }
        if (depth + 1 >= settings.max_depth) break;
        if (diffuse) {
            if (nee) result += direct_light(si, ray.d, m, throughput, rng);
            for (int i = 0; i < light.size; ++i)
                if (depth + 1 + light.vertices[i].hits <= settings.max_depth)
                    result += connect(si, ray.d, m, throughput, light.vertices[i], rng);
            if (light_tracing) {
                if (depth == 0) {
                    chain_density = camera_.area_density(si.p, si.n) / kPi;
                } else if (previous_diffuse) {
                    const Vec3 from_previous = si.p - previous;
                    chain_density = connection_density_over_pi(dot(ray.d, previous_facing), dot(ray.d, si.n),
                                                               dot(from_previous, from_previous));
                }
                chain = depth == 0 || previous_diffuse ? 1 : chain > 0 ? chain + 1 : 0;
            }
        }

        const BsdfSample bs = sample_bsdf(m, ray.d, si.n, rng);
        throughput *= bs.weight;
        if (is_black(throughput)) break;
        if (depth >= settings.rr_depth) {
            const double survive = std::min(1.0, max_component(throughput));
            if (rng.uniform() >= survive) break;
            throughput *= 1 / survive;
        }
        shape = extend(shape, diffuse);
        specular = bs.specular;
        previous_diffuse = diffuse;
        bsdf_pdf = bs.pdf;
        previous = si.p;
        previous_facing = dot(ray.d, si.n) < 0 ? si.n : -si.n;
        self = hit.prim;
        ray = spawn_ray(si, bs.wi);
    }
    return result;
}

}  // namespace glint
