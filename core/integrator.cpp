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

}  // namespace

Rgb PathTracer::direct_light(const SurfaceInteraction& si, const Vec3& d, const Material& m, Rng& rng) const {
    const double u_pick = rng.uniform(), u1 = rng.uniform(), u2 = rng.uniform();
    LightSample ls;
    const Vec3 facing = dot(d, si.n) < 0 ? si.n : -si.n;
    if (!scene_.lights().sample(si.p, si.prim, u_pick, u1, u2, ls, facing)) return Rgb{0};
    double bsdf_pdf;
    const Rgb f_cos = diffuse_f_cos(m, d, si.n, ls.wi, bsdf_pdf);
    if (is_black(f_cos)) return Rgb{0};
    Ray shadow = spawn_ray(si, ls.wi);
    shadow.tmax = ls.distance;
    if (scene_.geometry().occluded(shadow, si.prim, ls.prim)) return Rgb{0};
    return f_cos * ls.emission * (power_heuristic(ls.pdf, bsdf_pdf) / ls.pdf);
}

Rgb PathTracer::radiance(Ray ray, Rng& rng) const {
    const IntegratorSettings& settings = scene_.integrator();
    const bool nee = settings.light_sampling && !scene_.lights().empty();
    const bool light_tracing = scene_.light_tracing();
    Shape shape = Shape::camera;
    Rgb result{0}, throughput{1};
    uint32_t self = kNoPrimitive;
    bool specular = true;  // the camera "samples" its ray like a specular bounce: no MIS
    double bsdf_pdf = 0;
    Vec3 previous, previous_facing;
    for (int depth = 0;; ++depth) {
        Hit hit;
        if (!scene_.geometry().intersect(ray, self, hit)) {
            result += throughput * scene_.background();
            break;
        }
        const SurfaceInteraction si = scene_.geometry().interaction(ray, hit);
        const Material& m = scene_.material(hit.prim);
        const bool traced_from_light = light_tracing && shape == Shape::caustic &&
                                       scene_.caustic_emitter().covers(hit.prim, si.p, self);
        if (m.is_emissive() && !traced_from_light) {
            // Emission found by BSDF sampling; where NEE could also have found it, MIS-weight it.
            const double w = nee && !specular
                                 ? power_heuristic(bsdf_pdf, scene_.lights().pdf(previous, self, si, previous_facing))
                                 : 1.0;
            result += throughput * m.emission * w;
        }
        if (depth + 1 >= settings.max_depth) break;
        if (nee && m.type == MaterialType::diffuse) result += throughput * direct_light(si, ray.d, m, rng);

        const BsdfSample bs = sample_bsdf(m, ray.d, si.n, rng);
        throughput *= bs.weight;
        if (is_black(throughput)) break;
        if (depth >= settings.rr_depth) {
            const double survive = std::min(1.0, max_component(throughput));
            if (rng.uniform() >= survive) break;
            throughput *= 1 / survive;
        }
        shape = extend(shape, m.type == MaterialType::diffuse);
        specular = bs.specular;
        bsdf_pdf = bs.pdf;
        previous = si.p;
        previous_facing = dot(ray.d, si.n) < 0 ? si.n : -si.n;
        self = hit.prim;
        ray = spawn_ray(si, bs.wi);
    }
    return result;
}

}  // namespace glint
