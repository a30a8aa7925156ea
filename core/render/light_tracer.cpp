#include "render/light_tracer.h"

#include "render/mis.h"
#include "scene/bsdf.h"

namespace glint {

namespace {

// f toward the eye of light arriving along d_in, times |n_s·wi| / |n_g·wi|: a light path's weight
// is flux per unit of geometric area, so with a shading normal the adjoint BSDF takes that
// factor (Veach 1997, 5.3); evaluate() gives f·|n_s·wi|.
Rgb glossy_f(const Material& m, const SurfaceInteraction& si, const Vec3& d_in, const Vec3& to_eye) {
    const double cos_in = std::fabs(dot(si.n, d_in));
    if (!(cos_in > 0)) return Rgb{0};
    return Bsdf(m, si, to_eye).evaluate(to_eye, -d_in).f_cos * (1 / cos_in);
}

}  // namespace

void LightTracer::splat(const LightVertex& v, double w, const Material* glossy) const {
    const SurfaceInteraction& si = v.si;
    Camera::Projection proj;
    if (!camera_.project(si.p, proj)) return;
    const double cos_eye = dot(si.n, proj.to_eye);
    if (dot(v.d_in, si.n) * cos_eye >= 0) return;  // the eye is on the other side of the surface
    Ray shadow = spawn_ray(si, proj.to_eye);
    shadow.tmax = proj.distance - camera_.near();  // camera rays start `near` from the eye
    if (scene_.geometry().occluded(shadow, si.prim)) return;
    // Diffuse f = albedo/π; dω at the eye = |cos| dA / distance².
    const double pixels = double(width_) * height_;
    const Rgb value = glossy ? v.beta * glossy_f(*glossy, si, v.d_in, proj.to_eye) *
                                   (w * std::fabs(cos_eye) / (proj.distance * proj.distance) * proj.importance / pixels)
                             : v.beta * v.albedo *
                                   (w * std::fabs(cos_eye) / (kPi * proj.distance * proj.distance) * proj.importance / pixels);
    // The pixels whose filter footprint holds (fx, fy), within the window; y counts from the
    // bottom here, rows from the top in the window.
    const double margin = filter_margin(filter_);
    const int x0 = std::max(window_.x0, int(std::ceil(proj.fx - 1 - margin)));
    const int x1 = std::min(window_.x1 - 1, int(std::floor(proj.fx + margin)));
    const int y0 = std::max(height_ - window_.y1, int(std::ceil(proj.fy - 1 - margin)));
    const int y1 = std::min(height_ - 1 - window_.y0, int(std::floor(proj.fy + margin)));
    for (int row = y0; row <= y1; ++row)
        for (int x = x0; x <= x1; ++x) {
            const double f = filter_density(filter_, proj.fx - x, proj.fy - row);
            if (f > 0) film_.splat(x - window_.x0, height_ - 1 - row - window_.y0, value * f);
        }
}

bool LightTracer::to_diffuse(Ray ray, uint32_t self, uint32_t light, Rgb& throughput, int& hits, Rng& rng,
                             SurfaceInteraction& si, Vec3& d_in, bool glossy_ends) const {
    const IntegratorSettings& settings = scene_.integrator();
    for (bool first = true; ++hits <= settings.max_depth; first = false) {
        Hit hit;
        if (!scene_.geometry().intersect(ray, self, hit)) return false;
        const BsdfFlags flags = scene_.flags(hit.prim);
        const bool ends = flags.is_diffuse() || (glossy_ends && !flags.is_specular());
        // Other first surfaces are the path tracer's paths (or a connection's); a glossy surface
        // ends a light path, whose weights assume diffuse and specular vertices only (mis.h),
        // unless it is to be splatted alone.
        if (!ends && !flags.is_specular()) return false;
        if (first && (ends || (light != kNoPrimitive && !strategies_.caustic_emitter().is_target(light, hit.prim))))
            return false;
        si = scene_.interaction(ray, hit);
        d_in = ray.d;
        if (ends) return true;
        // Specular BSDFs carry no η², and their Fresnel terms are the same from either side
        // (Schlick's uses the outer cosine), so sampling them from the light side gives the
        // adjoint weights.
        Material scratch;
        const BsdfSample bs = Bsdf(scene_.material_at(si, scratch), si, -ray.d).sample(-ray.d, rng);
        throughput *= bs.weight;
        if (is_black(throughput)) return false;
        if (hits > settings.rr_depth) {
            const double survive = std::min(1.0, max_component(throughput));
            if (rng.uniform() >= survive) return false;
            throughput *= 1 / survive;
        }
        self = hit.prim;
        ray = spawn_ray(si, bs.wi);
    }
    return false;
}

// The first diffuse or glossy vertex of a path from the sun, splatted alone: the path tracer
// leaves these paths to light tracing. Nothing is handed back for connections, whose weights
// assume a light of area.
void LightTracer::sun_caustic(const EmittedRay& e, Rng& rng) const {
    Rgb throughput{1};
    int hits = 1;  // as a light's surface: the path tracer counts the escape as a bounce
    LightVertex v;
    if (!to_diffuse(e.ray, kNoPrimitive, kSunLight, throughput, hits, rng, v.si, v.d_in, true)) return;
    Material scratch;
    const Material& m = scene_.material_at(v.si, scratch);
    v.beta = e.weight * throughput;
    if (!scene_.flags(v.si.prim).is_diffuse()) return splat(v, 1, &m);
    v.albedo = Bsdf(m, v.si, -v.d_in).albedo();
    splat(v, 1);
}

LightPath LightTracer::trace(Rng& rng) const {
    const double u_pick = rng.uniform(), u1 = rng.uniform(), u2 = rng.uniform(), u3 = rng.uniform(),
                 u4 = rng.uniform();
    LightPath path;
    EmittedRay e;
    if (!strategies_.caustic_emitter().sample(u_pick, u1, u2, u3, u4, e)) return path;
    if (e.light == kSunLight) {
        sun_caustic(e, rng);
        return path;
    }
    Rgb throughput{1};
    int hits = 1;  // the light is the path's first surface hit; the path tracer caps them at max_depth
    uint32_t self = e.light;
    Ray ray = e.ray;
    for (uint32_t light = e.light; path.size < kLightVertices; light = kNoPrimitive) {
        LightVertex& v = path.vertices[path.size];
        if (!to_diffuse(ray, self, light, throughput, hits, rng, v.si, v.d_in)) break;
        Material scratch;
        const Bsdf bsdf(scene_.material_at(v.si, scratch), v.si, -v.d_in);
        v.beta = e.weight * throughput;
        v.albedo = bsdf.albedo();
        v.emitted_ratio = e.emitted_ratio;
        v.hits = hits;
        ++path.size;
        // y's camera-side partner is the eye alone (the path tracer leaves these paths to light
        // tracing); the later vertices' are weighed against the path tracer's.
        splat(v, path.size == 1 ? 1 : light_side_weight(camera_.area_density(v.si.p, v.si.n) / kPi, e.emitted_ratio));
        if (path.size == kLightVertices || hits >= scene_.integrator().max_depth) break;
        const BsdfSample bs = bsdf.sample(-v.d_in, rng);
        throughput *= bs.weight;
        if (is_black(throughput)) break;
        self = v.si.prim;
        ray = spawn_ray(v.si, bs.wi);
    }
    return path;
}

}  // namespace glint
