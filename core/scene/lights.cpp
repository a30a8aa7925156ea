#include "scene/lights.h"

#include <algorithm>

#include "base/sampling.h"
#include "scene/bsdf.h"

namespace glint {

LightSet::LightSet(const Geometry& geometry, const std::vector<Material>& materials,
                   const std::vector<uint32_t>& material_of_prim, OtherLights others)
    : geometry_(&geometry), light_of_prim_(geometry.primitive_count(), kNoLight) {
    std::vector<double> power;
    for (uint32_t prim = 0; prim < geometry.primitive_count(); ++prim) {
        const Material& m = materials[material_of_prim[prim]];
        if (!m.is_emissive()) continue;
        const double area = geometry.is_sphere(prim) ? geometry.sphere(prim).area()
                                                     : geometry.triangle(prim).area();
        if (!(area > 0)) continue;
        light_of_prim_[prim] = static_cast<uint32_t>(lights_.size());
        Light light{prim, m.emission};
        light.caps_begin = static_cast<uint32_t>(caps_.size());
        for (uint32_t o = 0; geometry.is_sphere(prim) && o < geometry.sphere_count(); ++o) {
            if (o == prim || Bsdf::flags(materials[material_of_prim[o]]).has(BsdfFlags::transmission)) continue;
            OccludedCap inside{o, true, {}}, outside{o, false, {}};
            if (SphereCap::beside(geometry.sphere(prim), geometry.sphere(o), true, inside.cap) &&
                SphereCap::beside(geometry.sphere(prim), geometry.sphere(o), false, outside.cap)) {
                caps_.push_back(inside);
                caps_.push_back(outside);
            }
        }
        light.caps_end = static_cast<uint32_t>(caps_.size());
        // Smallest first, so that visible_cap can stop at the first cap on p's side; stable, so
        // that of equal caps the first occluder's is chosen, whatever the sort.
        std::stable_sort(caps_.begin() + light.caps_begin, caps_.end(), [](const OccludedCap& a, const OccludedCap& b) {
            return a.cap.one_minus_cos < b.cap.one_minus_cos;
        });
        lights_.push_back(light);
        power.push_back(area * std::max(luminance(m.emission), 1e-300));
    }
    // Two-sided emitters are weighed by area × radiance, their power over 2π; the environment's
    // power through the scene's bounding sphere is π·r²·∫L dω, the sun's π·r²·irradiance.
    const Environment* environment = others.environment;
    const Sun* sun = others.sun;
    const double r = environment || sun ? bounding_radius(geometry) : 0;
    if (environment && environment->luminance_integral() > 0) {
        environment_ = environment;
        environment_index_ = power.size();
        power.push_back(0.5 * r * r * environment->luminance_integral());
    }
    if (sun && sun->selection_weight(r) > 0) {
        sun_ = sun;
        sun_index_ = power.size();
        power.push_back(sun->selection_weight(r));
    }
    points_index_ = power.size();
    for (const PointLight& light : others.points) {
        if (!(light.selection_weight() > 0)) continue;
        points_.push_back(light);
        power.push_back(light.selection_weight());
    }
    double total = 0;
    for (double p : power) cdf_.push_back(total += p);
    for (double& c : cdf_) c /= total;
    if (!cdf_.empty()) cdf_.back() = 1;
}

double LightSet::bounding_radius(const Geometry& geometry) {
    const Bounds3 box = geometry.bounds();
    const double r = 0.5 * length(box.hi - box.lo);
    return r > 0 && std::isfinite(r) ? r : 1;
}

bool LightSet::sample_environment(double u1, double u2, double share, LightSample& out) const {
    double pdf;
    if (!environment_->sample(u1, u2, out.wi, pdf)) return false;
    out.distance = kInfinity;
    out.emission = environment_->radiance(out.wi);
    out.prim = kNoPrimitive;
    out.pdf = pdf * share;
    return out.pdf > 0 && std::isfinite(out.pdf);
}

bool LightSet::sample_other(const Vec3& p, size_t index, double u1, double u2, double share, LightSample& out) const {
    if (index >= points_index_) return sample_point(p, points_[index - points_index_], share, out);
    if (environment_ && index == environment_index_) return sample_environment(u1, u2, share, out);
    return sample_sun(u1, u2, share, out);
}

bool LightSet::sample_point(const Vec3& p, const PointLight& light, double share, LightSample& out) const {
    const Vec3 to = light.position - p;
    const double dist2 = dot(to, to);
    if (!(dist2 > 0) || !std::isfinite(dist2)) return false;
    out.distance = std::sqrt(dist2);
    out.wi = to / out.distance;
    out.emission = light.intensity_toward(-out.wi) / dist2;
    out.prim = kNoPrimitive;
    out.delta = true;
    out.pdf = share;
    return !is_black(out.emission);
}

bool LightSet::sample_sun(double u1, double u2, double share, LightSample& out) const {
    double pdf;
    sun_->sample(u1, u2, out.wi, out.emission, pdf);
    out.distance = kInfinity;
    out.prim = kNoPrimitive;
    out.delta = sun_->is_delta();
    out.pdf = pdf * share;
    return out.pdf > 0 && std::isfinite(out.pdf);
}

double LightSet::pick_probability(size_t light) const {
    return cdf_[light] - (light == 0 ? 0 : cdf_[light - 1]);
}

// Seen from outside, a sphere is sampled within its cone; from inside, or from a point on its
// own surface (where inside/outside is decided by rounding), by area over the whole sphere.
double LightSet::cone_distance(const Vec3& p, uint32_t self, uint32_t prim) const {
    if (!geometry_->is_sphere(prim) || prim == self) return 0;
    const Sphere& s = geometry_->sphere(prim);
    const double distance = length(p - s.centre);
    return distance > s.radius ? distance : 0;
}

// The caps come smallest first, so the first on p's side is the smallest p can see: in smallpt's
// box, from anywhere inside it, the first (the ceiling's), found with one distance test instead
// of a square root for each of the five walls.
const SphereCap* LightSet::visible_cap(const Vec3& p, uint32_t self, const Vec3& facing, const Light& light,
                                       double distance) const {
    for (uint32_t i = light.caps_begin; i < light.caps_end; ++i) {
        const OccludedCap& c = caps_[i];
        const Sphere& o = geometry_->sphere(c.occluder);
        bool inside;
        if (c.occluder == self) {
            // p on its surface: rounding cannot tell the side, the side p looks from can.
            if (is_black(facing)) continue;
            inside = dot(facing, o.centre - p) > 0;
        } else {
            const Vec3 from_centre = p - o.centre;
            inside = dot(from_centre, from_centre) < o.radius * o.radius;
        }
        if (inside != c.inside) continue;
        const double horizon = 1 - geometry_->sphere(light.prim).radius / distance;
        return c.cap.one_minus_cos < horizon ? &c.cap : nullptr;
    }
    return nullptr;
}

double LightSet::area_pdf_to_solid_angle(double dist2, double cos_light, double area) {
    if (!(cos_light > 0) || !(dist2 > 0)) return 0;
    return dist2 / (cos_light * area);
}

double LightSet::area_pdf_to_solid_angle(const Vec3& p, const Vec3& q, const Vec3& nq, double area) {
    const Vec3 to = q - p;
    const double dist2 = dot(to, to);
    return area_pdf_to_solid_angle(dist2, std::fabs(dot(nq, to)) / std::sqrt(dist2), area);
}

double LightSet::toward(const Vec3& p, const Vec3& q, const Vec3& nq, double area, LightSample& out) {
    const Vec3 to = q - p;
    const double dist2 = dot(to, to);
    out.distance = std::sqrt(dist2);
    out.wi = to / out.distance;
    return area_pdf_to_solid_angle(dist2, std::fabs(dot(nq, to)) / out.distance, area);
}

bool LightSet::sample(const Vec3& p, uint32_t self, double u1, double u2, LightSample& out,
                      const Vec3& facing) const {
    if (cdf_.empty()) return false;
    const size_t index = std::min<size_t>(std::upper_bound(cdf_.begin(), cdf_.end(), u1) - cdf_.begin(),
                                          cdf_.size() - 1);
    // u1 picks the light and, stretched over the light's own share of [0, 1), places the point on
    // it: stratified (u1, u2) stay stratified over every light, where a separate random pick
    // would hand each triangle of a quad a random half of the strata.
    const double below = index == 0 ? 0 : cdf_[index - 1], share = cdf_[index] - below;  // pick_probability
    u1 = std::clamp((u1 - below) / share, 0.0, kOneMinusEpsilon);
    if (index >= lights_.size()) return sample_other(p, index, u1, u2, share, out);
    const Light& light = lights_[index];
    out.prim = light.prim;
    out.emission = light.emission;
    double pdf;
    const double dc = cone_distance(p, self, light.prim);
    const SphereCap* cap = dc > 0 ? visible_cap(p, self, facing, light, dc) : nullptr;
    if (cap) {
        const Sphere& s = geometry_->sphere(light.prim);
        const Vec3 n = cap->sample(u1, u2);
        const Vec3 q = s.centre + n * s.radius;
        if (!(dot(n, p - q) > 0)) return false;  // on the far side: the light hides it
        pdf = toward(p, q, n, cap->area(s), out);
    } else if (dc > 0) {
        const Sphere& s = geometry_->sphere(light.prim);
        const Vec3 axis = s.centre - p;
        const Cone cone = Cone::subtended(s.radius, dc);
        double sin2_theta;
        const Vec3 local = cone.sample(u1, u2, sin2_theta);
        out.wi = normalize(Frame::around(axis / dc).to_world(local));
        // Distance to the near side, as (dc² - r²) / (dc·cos θ + sqrt(r² - dc²·sin²θ)):
        // the textbook dc·cos θ - sqrt(...) cancels for tiny or nearly touching spheres.
        const double cos_theta = local.z;
        out.distance = (dc - s.radius) * (dc + s.radius) /
                       (dc * cos_theta + safe_sqrt(s.radius * s.radius - dc * dc * sin2_theta));
        pdf = cone.pdf();
    } else if (geometry_->is_sphere(light.prim)) {
        const Sphere& s = geometry_->sphere(light.prim);
        const Vec3 n = sample_uniform_sphere(u1, u2);
        pdf = toward(p, s.centre + n * s.radius, n, s.area(), out);
    } else {
        if (light.prim == self) return false;  // a flat light cannot light itself
        const Triangle& t = geometry_->triangle(light.prim);
        const Vec3 b = sample_uniform_triangle(u1, u2);
        const Vec3 q = t.v0 * b.x + t.v1 * b.y + t.v2 * b.z;
        out.b1 = b.y;
        out.b2 = b.z;
        pdf = toward(p, q, normalize(t.unnormalized_normal()), t.area(), out);
    }
    out.pdf = pdf * share;
    return out.pdf > 0 && std::isfinite(out.pdf) && out.distance > 0;
}

double LightSet::pdf(const Vec3& p, uint32_t self, const SurfaceInteraction& hit, const Vec3& facing) const {
    const uint32_t index = light_of_prim_[hit.prim];
    if (index == kNoLight) return 0;
    double pdf;
    const double dc = cone_distance(p, self, hit.prim);
    const SphereCap* cap = dc > 0 ? visible_cap(p, self, facing, lights_[index], dc) : nullptr;
    if (cap) {
        const Sphere& s = geometry_->sphere(hit.prim);
        if (!cap->contains(s, hit.p) || !(dot(hit.n, p - hit.p) > 0)) return 0;
        pdf = area_pdf_to_solid_angle(p, hit.p, hit.n, cap->area(s));
    } else if (dc > 0) {
        pdf = Cone::subtended(geometry_->sphere(hit.prim).radius, dc).pdf();
    } else if (geometry_->is_sphere(hit.prim)) {
        pdf = area_pdf_to_solid_angle(p, hit.p, hit.n, geometry_->sphere(hit.prim).area());
    } else {
        if (hit.prim == self) return 0;
        pdf = area_pdf_to_solid_angle(p, hit.p, hit.n, geometry_->triangle(hit.prim).area());
    }
    return pdf * pick_probability(index);
}

}  // namespace glint
