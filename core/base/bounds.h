// Axis-aligned boxes: Bounds3 in double for building, and the float box that BVH nodes store.
#pragma once

#include "base/float_rounding.h"
#include "base/math.h"

namespace glint {

struct Bounds3 {
    Vec3 lo{kInfinity};
    Vec3 hi{-kInfinity};

    void extend(const Vec3& p) { lo = min(lo, p); hi = max(hi, p); }
    void extend(const Bounds3& b) { lo = min(lo, b.lo); hi = max(hi, b.hi); }
    bool empty() const { return lo.x > hi.x; }
    Vec3 extent() const { return hi - lo; }
    Vec3 centre() const { return (lo + hi) * 0.5; }
    double half_area() const {
        if (empty()) return 0;
        const Vec3 e = extent();
        return e.x * e.y + e.y * e.z + e.z * e.x;
    }
};

// The box the two have in common; Bounds3{} when they have none (empty() looks at x only).
inline Bounds3 overlap(const Bounds3& a, const Bounds3& b) {
    const Bounds3 o{max(a.lo, b.lo), min(a.hi, b.hi)};
    return o.lo.x <= o.hi.x && o.lo.y <= o.hi.y && o.lo.z <= o.hi.z ? o : Bounds3{};
}

// Rounds a double box outward to float, so the stored box always contains the exact one.
struct FloatBox {
    float lo[3];
    float hi[3];

    static FloatBox enclosing(const Bounds3& b) {
        FloatBox f{};
        for (int a = 0; a < 3; ++a) {
            f.lo[a] = to_float_down(b.lo[a]);
            f.hi[a] = to_float_up(b.hi[a]);
        }
        return f;
    }
};

}  // namespace glint
