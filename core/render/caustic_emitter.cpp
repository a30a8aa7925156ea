#include "render/caustic_emitter.h"

#include <algorithm>

#include "base/sampling.h"
#include "scene/bsdf.h"

namespace glint {
namespace {

bool transmits(const Scene& scene, uint32_t prim) { return scene.flags(prim).has(BsdfFlags::transmission); }

// The spheres light tracing aims at: mirror and glass ones that emit nothing.
bool aimed_at(const Scene& scene, uint32_t prim) {
    return scene.flags(prim).is_specular() && !scene.material(prim).is_emissive();
}

}  // namespace

SphereCap CausticEmitter::cap_for(const Scene& scene, uint32_t light_prim, uint32_t target_prim) {
    const Geometry& geometry = scene.geometry();
    const Sphere &light = geometry.sphere(light_prim), &target = geometry.sphere(target_prim);
    const double dist = length(target.centre - light.centre);
    // Horizon: x sees some point of the target only if w·axis > (r - r_target) / dist.
    SphereCap best{(target.centre - light.centre) / dist, std::min(2.0, 1 - (light.radius - target.radius) / dist)};
    for (uint32_t prim = 0; prim < geometry.sphere_count(); ++prim) {
        if (prim == light_prim || prim == target_prim || transmits(scene, prim))
            continue;
        const Sphere& o = geometry.sphere(prim);
        const double target_dist = length(target.centre - o.centre);
        const bool inside = target_dist + target.radius < o.radius, outside = target_dist - target.radius > o.radius;
        SphereCap cap;
        if ((inside || outside) && SphereCap::beside(light, o, inside, cap) && cap.one_minus_cos < best.one_minus_cos)
            best = cap;
    }
    return best;
}

CausticEmitter::CausticEmitter(const Scene& scene) : geometry_(&scene.geometry()), sun_(scene.sun()) {
    std::vector<double> flux;
    add_sphere_light_pairs(scene, flux);
    add_sun_pairs(scene, flux);
    double total = 0;
    for (double f : flux) cdf_.push_back(total += f);
    for (double& c : cdf_) c /= total;
    if (!cdf_.empty()) cdf_.back() = 1;
}

void CausticEmitter::add_sphere_light_pairs(const Scene& scene, std::vector<double>& flux) {
    const Geometry& geometry = scene.geometry();
    for (uint32_t light = 0; light < geometry.sphere_count(); ++light) {
        const Material& lm = scene.material(light);
        // A textured light's emission varies over it: left to the path tracer.
        if (!lm.is_emissive() || lm.maps != Material::kNoMaps) continue;
        const Sphere& ls = geometry.sphere(light);
        for (uint32_t target = 0; target < geometry.sphere_count(); ++target) {
            if (!aimed_at(scene, target)) continue;
            const Sphere& ts = geometry.sphere(target);
            const double dist = length(ts.centre - ls.centre);
            if (!(dist > ls.radius + ts.radius)) continue;  // overlapping: leave to the path tracer
            const SphereCap cap = cap_for(scene, light, target);
            if (!(cap.one_minus_cos > 0)) continue;
            pairs_.push_back({light, target, cap, lm.emission});
            // Roughly the flux the target intercepts: radiance × cap area × the target's solid angle.
            flux.push_back(luminance(lm.emission) * cap.area(ls) * (ts.radius * ts.radius) / (dist * dist));
        }
    }
}

void CausticEmitter::add_sun_pairs(const Scene& scene, std::vector<double>& flux) {
    if (!sun_ || is_black(sun_->settings().irradiance)) return;
    const Geometry& geometry = scene.geometry();
    // Its light paths end at the first surface they meet that is not specular: without one they
    // are cost alone.
    bool any_receiver = false;
    for (uint32_t prim = 0; prim < geometry.primitive_count() && !any_receiver; ++prim)
        any_receiver = !scene.flags(prim).is_specular();
    if (!any_receiver) return;
    const Bounds3 box = geometry.bounds();
    const Vec3 centre = (box.lo + box.hi) * 0.5;
    const double radius = 0.5 * length(box.hi - box.lo);
    for (uint32_t target = 0; target < geometry.sphere_count(); ++target) {
        if (!aimed_at(scene, target)) continue;
        const Sphere& ts = geometry.sphere(target);
        pairs_.push_back({kSunLight, target, {}, Rgb{0}, length(ts.centre - centre) + radius + ts.radius});
        // The flux through the sphere's disc.
        flux.push_back(luminance(sun_->settings().irradiance) * kPi * ts.radius * ts.radius);
    }
}

// A direction toward the sun, then a point of the target's disc across it, uniform: every ray
// of that direction that meets the target passes through the disc.
bool CausticEmitter::sample_sun(const Pair& pair, double choice, double u1, double u2, double u3, double u4,
                                EmittedRay& out) const {
    Vec3 toward;
    Rgb value;
    double pdf;
    sun_->sample(u1, u2, toward, value, pdf);
    const Sphere& ts = geometry_->sphere(pair.target);
    double x, y;
    sample_disk(u3, u4, x, y);
    const Vec3 disc = Frame::around(toward).to_world(Vec3{x, y, 0}) * ts.radius;
    out.ray = Ray{ts.centre + disc + toward * pair.far, -toward};
    out.emitted_ratio = 0;
    out.weight = value * (kPi * ts.radius * ts.radius / (pdf * choice));
    out.light = kSunLight;
    return true;
}

const CausticEmitter::Pair* CausticEmitter::find(uint32_t light, uint32_t target) const {
    for (const Pair& p : pairs_)
        if (p.light == light && p.target == target) return &p;
    return nullptr;
}

bool CausticEmitter::covers(uint32_t light, const Vec3& x, uint32_t target) const {
    const Pair* pair = find(light, target);
    return pair != nullptr && pair->cap.contains(geometry_->sphere(light), x);
}

double CausticEmitter::pdf(uint32_t light, const Vec3& x, const Vec3& d) const { return pdf(light, kNone, x, d); }

double CausticEmitter::pdf(uint32_t light, size_t chosen, const Vec3& x, const Vec3& d) const {
    double total = 0;
    for (size_t i = 0; i < pairs_.size(); ++i) {
        const Pair& p = pairs_[i];
        if (p.light != light) continue;
        const Sphere &ls = geometry_->sphere(p.light), &ts = geometry_->sphere(p.target);
        const Vec3 to = ts.centre - x;
        const double dist = length(to);
        const Cone cone = Cone::subtended(ts.radius, dist);
        // The chosen pair produced (x, d): counted without re-testing, which rounding could fail.
        if (i != chosen && (!p.cap.contains(ls, x) || 1 - dot(d, to) / dist > cone.one_minus_cos_max)) continue;
        const double choice = cdf_[i] - (i == 0 ? 0 : cdf_[i - 1]);
        total += choice / p.cap.area(ls) * cone.pdf();
    }
    return total;
}

bool CausticEmitter::sample(double u_pick, double u1, double u2, double u3, double u4, EmittedRay& out) const {
    if (pairs_.empty()) return false;
    const size_t chosen =
        std::min<size_t>(std::upper_bound(cdf_.begin(), cdf_.end(), u_pick) - cdf_.begin(), pairs_.size() - 1);
    const Pair& pair = pairs_[chosen];
    if (pair.light == kSunLight)
        return sample_sun(pair, cdf_[chosen] - (chosen == 0 ? 0 : cdf_[chosen - 1]), u1, u2, u3, u4, out);
    const Sphere &ls = geometry_->sphere(pair.light), &ts = geometry_->sphere(pair.target);
    const Vec3 w = pair.cap.sample(u1, u2);
    const Vec3 x = ls.centre + w * ls.radius;
    const Vec3 to = ts.centre - x;
    const double dist = length(to);
    double sin2;
    const Vec3 d = normalize(Frame::around(to / dist).to_world(Cone::subtended(ts.radius, dist).sample(u3, u4, sin2)));
    const double cos_out = dot(w, d);
    if (!(cos_out > 0)) return false;  // into the light itself
    const double pdf_xd = pdf(pair.light, chosen, x, d);
    if (!(pdf_xd > 0) || !std::isfinite(pdf_xd)) return false;
    out.ray = Ray{x, d};
    out.emitted_ratio = cos_out / pdf_xd;
    out.weight = pair.emission * out.emitted_ratio;
    out.light = pair.light;
    return true;
}

}  // namespace glint
