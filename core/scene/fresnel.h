// Fresnel reflectances: Schlick's approximation and the exact unpolarised dielectric equations.
#pragma once

#include "base/math.h"

namespace glint {

// Schlick's approximation F0 + (1 - F0)(1 - c)^5, for the cosine c on the side it is taken.
template <typename T>
T schlick(const T& f0, double c) {
    const double m = std::clamp(1 - c, 0.0, 1.0), m2 = m * m;
    return f0 + (T(1) - f0) * (m2 * m2 * m);
}

// F0 of an interface between indices 1 and ior.
inline double dielectric_f0(double ior) {
    const double r = (ior - 1) / (ior + 1);
    return r * r;
}

// The unpolarised reflectance of a smooth dielectric interface, light arriving at cosine cos_i
// (> 0) from the side of index 1 toward index eta (the ratio of the far side's to the near
// side's); 1 under total internal reflection.
inline double fresnel_dielectric(double cos_i, double eta) {
    const double sin2_t = (1 - cos_i * cos_i) / (eta * eta);
    if (sin2_t >= 1) return 1;
    const double cos_t = std::sqrt(1 - sin2_t);
    const double parallel = (eta * cos_i - cos_t) / (eta * cos_i + cos_t);
    const double perpendicular = (cos_i - eta * cos_t) / (cos_i + eta * cos_t);
    return 0.5 * (parallel * parallel + perpendicular * perpendicular);
}

}  // namespace glint
