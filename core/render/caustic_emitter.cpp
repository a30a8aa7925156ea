#include "render/caustic_emitter.h"

#include <algorithm>

#include "base/sampling.h"
#include "scene/bsdf.h"

namespace glint {
namespace {

bool transmits(const Scene& scene, uint32_t prim) { return scene.flags(prim).has(BsdfFlags::transmission); }

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

CausticEmitter::CausticEmitter(const Scene& scene) : geometry_(&scene.geometry()) {
    const Geometry& geometry = scene.geometry();
    std::vector<double> flux;
    for (uint32_t light = 0; light < geometry.sphere_count(); ++light) {
        const Material& lm = scene.material(light);
        // A textured light's emission varies over it: left to the path tracer.
        if (!lm.is_emissive() || lm.maps != Material::kNoMaps) continue;
        const Sphere& ls = geometry.sphere(light);
        for (uint32_t target = 0; target < geometry.sphere_count(); ++target) {
            const Material& tm = scene.material(target);
            if (!scene.flags(target).is_specular() || tm.is_emissive()) continue;
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
    double total = 0;
    for (double f : flux) cdf_.push_back(total += f);
    for (double& c : cdf_) c /= total;
    if (!cdf_.empty()) cdf_.back() = 1;
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
