#include "lights.h"

#include <algorithm>

#include "sampling.h"

namespace glint {

LightSet::LightSet(const Geometry& geometry, const std::vector<Material>& materials,
                   const std::vector<uint32_t>& material_of_prim)
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
        light.occluders_begin = light.occluders_end = static_cast<uint32_t>(occluders_.size());
        for (uint32_t o = 0; geometry.is_sphere(prim) && o < geometry.sphere_count(); ++o) {
            if (o == prim || materials[material_of_prim[o]].type == MaterialType::glass) continue;
            Occluder occ{o, {}, {}};
            if (SphereCap::beside(geometry.sphere(prim), geometry.sphere(o), true, occ.inside) &&
                SphereCap::beside(geometry.sphere(prim), geometry.sphere(o), false, occ.outside)) {
                occluders_.push_back(occ);
                ++light.occluders_end;
            }
        }
        lights_.push_back(light);
        power.push_back(area * std::max(luminance(m.emission), 1e-300));
    }
    double total = 0;
    for (double p : power) cdf_.push_back(total += p);
    for (double& c : cdf_) c /= total;
    if (!cdf_.empty()) cdf_.back() = 1;
}

double LightSet::pick_probability(size_t light) const {
    return cdf_[light] - (light == 0 ? 0 : cdf_[light - 1]);
}

// Seen from outside, a sphere is sampled within its cone; from inside, or from a point on its
// own surface (where inside/outside is decided by rounding), by area over the whole sphere.
bool LightSet::sees_as_cone(const Vec3& p, uint32_t self, uint32_t prim) const {
    if (!geometry_->is_sphere(prim) || prim == self) return false;
    const Sphere& s = geometry_->sphere(prim);
    return length(p - s.centre) > s.radius;
}

bool LightSet::visible_cap(const Vec3& p, uint32_t self, const Vec3& facing, const Light& light,
                           SphereCap& cap) const {
    const Sphere& s = geometry_->sphere(light.prim);
    double best = 1 - s.radius / length(p - s.centre);  // the horizon
    bool found = false;
    for (uint32_t i = light.occluders_begin; i < light.occluders_end; ++i) {
        const Occluder& occ = occluders_[i];
        const Sphere& o = geometry_->sphere(occ.prim);
        bool inside = length(p - o.centre) < o.radius;
        if (occ.prim == self) {
            // p on its surface: rounding cannot tell the side, the side p looks from can.
            if (is_black(facing)) continue;
            inside = dot(facing, o.centre - p) > 0;
        }
        const SphereCap& side = inside ? occ.inside : occ.outside;
        if (side.one_minus_cos < best) {
            best = side.one_minus_cos;
            cap = side;
            found = true;
        }
    }
    return found;
}

double LightSet::area_pdf_to_solid_angle(const Vec3& p, const Vec3& q, const Vec3& nq, double area) {
    const Vec3 to = q - p;
    const double dist2 = dot(to, to);
    const double cos_light = std::fabs(dot(nq, to)) / std::sqrt(dist2);
    if (!(cos_light > 0) || !(dist2 > 0)) return 0;
    return dist2 / (cos_light * area);
}

bool LightSet::sample(const Vec3& p, uint32_t self, double u_pick, double u1, double u2, LightSample& out,
                      const Vec3& facing) const {
    if (lights_.empty()) return false;
    const size_t index = std::min<size_t>(std::upper_bound(cdf_.begin(), cdf_.end(), u_pick) - cdf_.begin(),
                                          lights_.size() - 1);
    const Light& light = lights_[index];
    out.prim = light.prim;
    out.emission = light.emission;
    double pdf;
    SphereCap cap;
    if (sees_as_cone(p, self, light.prim) && visible_cap(p, self, facing, light, cap)) {
        const Sphere& s = geometry_->sphere(light.prim);
        const Vec3 n = cap.sample(u1, u2);
        const Vec3 q = s.centre + n * s.radius;
        if (!(dot(n, p - q) > 0)) return false;  // on the far side: the light hides it
        pdf = area_pdf_to_solid_angle(p, q, n, cap.area(s));
        out.distance = length(q - p);
        out.wi = (q - p) / out.distance;
    } else if (sees_as_cone(p, self, light.prim)) {
        const Sphere& s = geometry_->sphere(light.prim);
        const Vec3 axis = s.centre - p;
        const double dc = length(axis);
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
        const Vec3 q = s.centre + n * s.radius;
        pdf = area_pdf_to_solid_angle(p, q, n, s.area());
        out.distance = length(q - p);
        out.wi = (q - p) / out.distance;
    } else {
        if (light.prim == self) return false;  // a flat light cannot light itself
        const Triangle& t = geometry_->triangle(light.prim);
        const Vec3 b = sample_uniform_triangle(u1, u2);
        const Vec3 q = t.v0 * b.x + t.v1 * b.y + t.v2 * b.z;
        pdf = area_pdf_to_solid_angle(p, q, normalize(t.unnormalized_normal()), t.area());
        out.distance = length(q - p);
        out.wi = (q - p) / out.distance;
    }
    out.pdf = pdf * pick_probability(index);
    return out.pdf > 0 && std::isfinite(out.pdf) && out.distance > 0;
}

double LightSet::pdf(const Vec3& p, uint32_t self, const SurfaceInteraction& hit, const Vec3& facing) const {
    const uint32_t index = light_of_prim_[hit.prim];
    if (index == kNoLight) return 0;
    double pdf;
    SphereCap cap;
    if (sees_as_cone(p, self, hit.prim) && visible_cap(p, self, facing, lights_[index], cap)) {
        const Sphere& s = geometry_->sphere(hit.prim);
        if (!cap.contains(s, hit.p) || !(dot(hit.n, p - hit.p) > 0)) return 0;
        pdf = area_pdf_to_solid_angle(p, hit.p, hit.n, cap.area(s));
    } else if (sees_as_cone(p, self, hit.prim)) {
        const Sphere& s = geometry_->sphere(hit.prim);
        pdf = Cone::subtended(s.radius, length(s.centre - p)).pdf();
    } else if (geometry_->is_sphere(hit.prim)) {
        pdf = area_pdf_to_solid_angle(p, hit.p, hit.n, geometry_->sphere(hit.prim).area());
    } else {
        if (hit.prim == self) return 0;
        pdf = area_pdf_to_solid_angle(p, hit.p, hit.n, geometry_->triangle(hit.prim).area());
    }
    return pdf * pick_probability(index);
}

}  // namespace glint
