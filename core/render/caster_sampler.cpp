#include "render/caster_sampler.h"

#include "base/sampling.h"
#include "scene/bsdf.h"

namespace glint {

CasterSampler::CasterSampler(const Scene& scene) {
    const Geometry& geometry = scene.geometry();
    for (uint32_t prim = 0; prim < geometry.primitive_count(); ++prim)
        if (geometry.is_sphere(prim) && scene.flags(prim).is_specular())
            casters_.push_back({geometry.sphere(prim).centre, geometry.sphere(prim).radius});
}

bool CasterSampler::Caster::outside(const Vec3& p) const {
    const Vec3 to_centre = centre - p;
    return dot(to_centre, to_centre) > radius * radius;
}

bool CasterSampler::Caster::holds(const Vec3& p, const Vec3& wi) const {
    // In the cone: in front of p, and the line passes within the radius of the centre (the
    // cross product's length is that distance, without the cancellation of |oc|² - (oc·wi)²).
    const Vec3 to_centre = centre - p;
    const Vec3 c = cross(to_centre, wi);
    return dot(to_centre, wi) > 0 && dot(c, c) <= radius * radius;
}

int CasterSampler::count_outside(const Vec3& p) const {
    int n = 0;
    for (const Caster& c : casters_) n += c.outside(p);
    return n;
}

bool CasterSampler::sample(const Vec3& p, double u_pick, double u1, double u2, Vec3& wi, double& pdf_out) const {
    const int n = count_outside(p);
    if (n == 0) return false;
    int pick = std::min(n - 1, int(u_pick * n));
    for (const Caster& c : casters_) {
        if (!c.outside(p) || pick-- > 0) continue;
        const Vec3 axis = c.centre - p;
        const double distance = length(axis);
        double sin2_theta;
        const Vec3 local = Cone::subtended(c.radius, distance).sample(u1, u2, sin2_theta);
        wi = normalize(Frame::around(axis / distance).to_world(local));
        pdf_out = density(p, wi, &c);
        return true;
    }
    return false;
}

double CasterSampler::pdf(const Vec3& p, const Vec3& wi) const { return density(p, wi, nullptr); }

double CasterSampler::density(const Vec3& p, const Vec3& wi, const Caster* chosen) const {
    const int n = count_outside(p);
    double sum = 0;
    for (const Caster& c : casters_)
        if (c.outside(p) && (&c == chosen || c.holds(p, wi)))
            sum += Cone::subtended(c.radius, length(c.centre - p)).pdf();
    return n > 0 ? sum / n : 0;
}

}  // namespace glint
