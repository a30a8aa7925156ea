// A ray o + t·d for t in (tmin, tmax] (Embree's convention, which the shared ray sets use).
// Directions are unit length wherever glint creates them.
#pragma once

#include "math.h"

namespace glint {

struct Ray {
    Vec3 o;
    Vec3 d;
    double tmin = 0;
    double tmax = kInfinity;
};

// The primitive a ray leaves from, so that intersection can rule out re-hitting it (see
// Sphere::intersect and Triangle::intersect); kNoPrimitive for camera rays.
inline constexpr uint32_t kNoPrimitive = 0xFFFFFFFFu;

}  // namespace glint
