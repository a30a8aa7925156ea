#include "scene/environment.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace glint {

Environment::Environment(std::shared_ptr<const EnvironmentMap> map, EnvironmentSettings settings)
    : map_(std::move(map)), settings_(settings), rotation_radians_(settings.rotation * kPi / 180) {
    if (!map_) throw std::invalid_argument("environment: no map");
}

void Environment::to_image(const Vec3& d, double& u, double& v) const {
    u = 0.5 + (std::atan2(d.z, d.x) + rotation_radians_) / (2 * kPi);
    u -= std::floor(u);
    v = 0.5 - std::asin(std::clamp(d.y, -1.0, 1.0)) / kPi;
    if (!(u >= 0 && u < 1)) u = 0;  // NaN, or 1 by rounding
    if (!(v >= 0 && v <= 1)) v = 0;
}

Rgb Environment::radiance(const Vec3& d) const {
    double u, v;
    to_image(d, u, v);
    return map_->lookup(u, v) * settings_.strength;
}

bool Environment::sample(double u1, double u2, Vec3& d, double& pdf) const {
    double u, z;
    if (!map_->sample(u1, u2, u, z, pdf)) return false;
    const double phi = 2 * kPi * (u - 0.5) - rotation_radians_;
    const double cos_theta = std::sqrt(std::max(0.0, 1 - z * z));
    d = Vec3{cos_theta * std::cos(phi), z, cos_theta * std::sin(phi)};
    return true;
}

double Environment::pdf(const Vec3& d) const {
    double u, v;
    to_image(d, u, v);
    return map_->pdf(u, v);
}

}  // namespace glint
