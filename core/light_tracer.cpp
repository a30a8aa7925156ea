#include "light_tracer.h"

namespace glint {

void LightTracer::splat(const SurfaceInteraction& si, const Vec3& d_in, const Material& m, const Rgb& beta) const {
    Camera::Projection proj;
    if (!camera_.project(si.p, proj)) return;
    const double cos_eye = dot(si.n, proj.to_eye);
    if (dot(d_in, si.n) * cos_eye >= 0) return;  // the eye is on the other side of the surface
    Ray shadow = spawn_ray(si, proj.to_eye);
    shadow.tmax = proj.distance - camera_.near();  // camera rays start `near` from the eye
    if (scene_.geometry().occluded(shadow, si.prim)) return;
    // Diffuse f = albedo/π; dω at the eye = |cos| dA / distance².
    const double pixels = double(film_.width()) * film_.height();
    const Rgb value = beta * m.albedo *
                      (std::fabs(cos_eye) / (kPi * proj.distance * proj.distance) * proj.importance / pixels);
    // The pixels whose filter footprint holds (fx, fy); y counts from the bottom here.
    const double margin = filter_margin(filter_);
    const int x0 = std::max(0, int(std::ceil(proj.fx - 1 - margin)));
    const int x1 = std::min(film_.width() - 1, int(std::floor(proj.fx + margin)));
    const int y0 = std::max(0, int(std::ceil(proj.fy - 1 - margin)));
    const int y1 = std::min(film_.height() - 1, int(std::floor(proj.fy + margin)));
    for (int row = y0; row <= y1; ++row)
        for (int x = x0; x <= x1; ++x) {
            const double w = filter_density(filter_, proj.fx - x, proj.fy - row);
            if (w > 0) film_.splat(x, film_.height() - 1 - row, value * w);
        }
}

void LightTracer::trace(Rng& rng) const {
    const IntegratorSettings& settings = scene_.integrator();
    const CausticEmitter& emitter = scene_.caustic_emitter();
    const double u_pick = rng.uniform(), u1 = rng.uniform(), u2 = rng.uniform(), u3 = rng.uniform(),
                 u4 = rng.uniform();
    EmittedRay e;
    if (!emitter.sample(u_pick, u1, u2, u3, u4, e)) return;
    Ray ray = e.ray;
    uint32_t self = e.light;
    Rgb throughput{1};
    // The light is the path's first surface hit; the path tracer caps the hits at max_depth.
    for (int hits = 2; hits <= settings.max_depth; ++hits) {
        Hit hit;
        if (!scene_.geometry().intersect(ray, self, hit)) return;
        if (hits == 2 && !emitter.is_target(e.light, hit.prim)) return;  // the path tracer's path
        const SurfaceInteraction si = scene_.geometry().interaction(ray, hit);
        const Material& m = scene_.material(hit.prim);
        if (m.type == MaterialType::diffuse) {
            splat(si, ray.d, m, e.weight * throughput);
            return;
        }
        // smallpt's BSDFs carry no η² and Schlick's term uses the outer cosine, so sampling
        // them from the light side gives the adjoint weights.
        const BsdfSample bs = sample_bsdf(m, ray.d, si.n, rng);
        throughput *= bs.weight;
        if (is_black(throughput)) return;
        if (hits > settings.rr_depth) {
            const double survive = std::min(1.0, max_component(throughput));
            if (rng.uniform() >= survive) return;
            throughput *= 1 / survive;
        }
        self = hit.prim;
        ray = spawn_ray(si, bs.wi);
    }
}

}  // namespace glint
