// The slab test of one ray against the four child boxes of a BVH node at once, in SSE single
// precision, made conservative: it never rejects a box that the exact test with the double ray
// would accept.
//
// Three sources of error, three remedies:
// - The double origin is rounded to float in the direction that can only widen each slab's
//   interval (up for the near plane of a positive direction, down for its far plane, and the
//   other way round for a negative one), so the rounded origins bracket the exact one.
// - Subtraction, multiplication and the rounded reciprocal each round once: far distances are
//   scaled by more than 1 + 2·gamma(3), which Ize ("Robust BVH ray traversal", JCGT 2013) shows
//   suffices.
// - A zero direction component gives an infinite reciprocal, and a ray lying in a slab's plane
//   gives 0·inf = NaN. MAXPS and MINPS return their second operand when either is NaN, so with
//   the running interval as second operand a NaN never narrows it: the ray is inside that slab
//   for every t.
#pragma once

#if !defined(__SSE2__)
#error "glint's BVH traversal needs SSE2 (every x86-64 processor has it)"
#endif

#include <immintrin.h>

#include <cmath>

#include "float_rounding.h"
#include "ray.h"

namespace glint {

// Four child boxes in structure-of-arrays order: planes[2·axis] holds the four lower bounds
// along that axis, planes[2·axis + 1] the four upper ones. An unused slot has lo = +inf and
// hi = -inf, which no ray can enter.
struct alignas(16) WideBox {
    float planes[6][4];
};

class RayBoxTest {
public:
    explicit RayBoxTest(const Ray& ray) {
        for (int a = 0; a < 3; ++a) {
            const float inv = to_float_nearest(1.0 / ray.d[a]);
            const bool negative = std::signbit(inv);  // -0 counts as negative, like its -inf
            near_plane_[a] = 2 * a + negative;
            far_plane_[a] = 2 * a + !negative;
            const float up = to_float_up(ray.o[a]), down = to_float_down(ray.o[a]);
            near_origin_[a] = _mm_set1_ps(negative ? down : up);
            far_origin_[a] = _mm_set1_ps(negative ? up : down);
            inv_[a] = _mm_set1_ps(inv);
        }
        tmin_ = _mm_set1_ps(to_float_down(ray.tmin));
    }

    // Bit i of the result is set when box i overlaps the ray in (tmin, tmax]; `entry` receives
    // the four entry distances. `tmax` is the ray's limit rounded up to float.
    int hit(const WideBox& box, float tmax, __m128& entry) const {
        __m128 t_near = tmin_;
        __m128 t_far = _mm_set1_ps(std::numeric_limits<float>::infinity());
        for (int a = 0; a < 3; ++a) {
            const __m128 n = _mm_mul_ps(_mm_sub_ps(_mm_load_ps(box.planes[near_plane_[a]]), near_origin_[a]), inv_[a]);
            const __m128 f = _mm_mul_ps(_mm_sub_ps(_mm_load_ps(box.planes[far_plane_[a]]), far_origin_[a]), inv_[a]);
            t_near = _mm_max_ps(n, t_near);
            t_far = _mm_min_ps(f, t_far);
        }
        constexpr float kPad = 1 + 0x1p-20f;  // above 1 + 2·gamma(3), with room for its own rounding
        t_far = _mm_min_ps(_mm_mul_ps(t_far, _mm_set1_ps(kPad)), _mm_set1_ps(tmax));
        entry = t_near;
        return _mm_movemask_ps(_mm_cmple_ps(t_near, t_far));
    }

private:
    __m128 near_origin_[3], far_origin_[3], inv_[3], tmin_;
    int near_plane_[3], far_plane_[3];
};

}  // namespace glint
