// A ray o + t·d for t in (tmin, tmax] (Embree's convention, which the shared ray sets use).
// Directions are unit length wherever glint creates them.
#pragma once

#include <emmintrin.h>

#include <cstddef>
#include <cstring>

#include "base/math.h"

namespace glint {

struct Ray {
    Vec3 o;
    Vec3 d;
    double tmin = 0;
    double tmax = kInfinity;
};

static_assert(offsetof(Ray, d) == 3 * sizeof(double), "o and d are six consecutive doubles");

// Whether the origin and direction are finite: three two-lane comparisons of their magnitudes
// with infinity (false for NaN), not six scalar tests and branches; every query of a ray asks it.
inline bool has_finite_origin_and_direction(const Ray& ray) {
    double v[6];
    std::memcpy(v, &ray.o, sizeof v);
    const __m128d magnitude = _mm_set1_pd(-0.0), inf = _mm_set1_pd(kInfinity);
    const auto finite = [&](int i) { return _mm_cmplt_pd(_mm_andnot_pd(magnitude, _mm_loadu_pd(v + i)), inf); };
    return _mm_movemask_pd(_mm_and_pd(_mm_and_pd(finite(0), finite(2)), finite(4))) == 3;
}

// The primitive a ray leaves from, so that intersection can rule out re-hitting it (see
// Sphere::intersect and Triangle::intersect); kNoPrimitive for camera rays.
inline constexpr uint32_t kNoPrimitive = 0xFFFFFFFFu;

}  // namespace glint
