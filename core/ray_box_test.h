// The slab test of one ray against the eight child boxes of a BVH node at once, in AVX single
// precision, made conservative: it never rejects a box that the exact test with the double ray
// would accept.
//
// Three sources of error, three remedies:
// - The double origin is rounded to float in the direction that can only widen each slab's
//   interval (up for the near plane of a positive direction, down for its far plane, and the
//   other way round for a negative one), so the rounded origins bracket the exact one.
// - Subtraction, multiplication and the rounded reciprocal each round once: far distances are
//   scaled by more than 1 + 2·gamma(3), which Ize ("Robust BVH ray traversal", JCGT 2013) shows
//   suffices. The scale is folded into the far planes' reciprocals (one rounding more, four in
//   all, against a scale of 1 + 2^-20 = 1 + 16u), so it costs no instruction per node. Only the
//   far distances change: the entry distances, which order the traversal, are as before.
// - A zero direction component gives an infinite reciprocal, and a ray lying in a slab's plane
//   gives 0·inf = NaN. VMAXPS and VMINPS return their second operand when either is NaN, so with
//   the running interval as second operand a NaN never narrows it: the ray is inside that slab
//   for every t.
#pragma once

#if !defined(__AVX2__)
#error "glint's BVH traversal needs AVX2 (CMakeLists.txt passes -mavx2)"
#endif

#include <immintrin.h>

#include <array>
#include <cmath>
#include <cstdint>

#include "float_rounding.h"
#include "ray.h"

namespace glint {

inline constexpr int kBvhWidth = 8;

// Eight child boxes in structure-of-arrays order: planes[2·axis] holds the eight lower bounds
// along that axis, planes[2·axis + 1] the eight upper ones. An unused slot has lo = +inf and
// hi = -inf, which no ray can enter.
struct alignas(32) WideBox {
    float planes[6][kBvhWidth];
};

class RayBoxTest {
public:
    explicit RayBoxTest(const Ray& ray) {
        // Rounded four at a time: the origin up, the origin and tmin down, the reciprocals to
        // nearest. A negative reciprocal (-0's -inf included) swaps an axis' near and far
        // planes, so its sign bit picks the rounding for each: no branch per axis.
        const __m256d origin_tmin = _mm256_setr_pd(ray.o.x, ray.o.y, ray.o.z, ray.tmin);
        const __m128 up = to_float_up(origin_tmin), down = to_float_down(origin_tmin);
        const __m128 inv = _mm256_cvtpd_ps(_mm256_div_pd(_mm256_set1_pd(1.0), _mm256_setr_pd(ray.d.x, ray.d.y, ray.d.z, 1.0)));
        constexpr float kPad = 1 + 0x1p-20f;  // above 1 + 2·gamma(4), with room for its own rounding
        const __m128 far_inv = _mm_mul_ps(inv, _mm_set1_ps(kPad));
        const __m128 near = _mm_blendv_ps(up, down, inv), far = _mm_blendv_ps(down, up, inv);
        offsets_ = &kPlaneOffsets[_mm_movemask_ps(inv) & 7];
        for (int a = 0; a < 3; ++a) {
            near_origin_[a] = lane(near, a);
            far_origin_[a] = lane(far, a);
            inv_[a] = lane(inv, a);
            far_inv_[a] = lane(far_inv, a);
        }
        tmin_ = lane(down, 3);
    }

    // Bit i of the result is set when box i overlaps the ray in (tmin, tmax]; `entry` receives
    // the eight entry distances. `tmax` is the ray's limit rounded up to float, in every lane.
    int hit(const WideBox& box, __m256 tmax, __m256& entry) const {
        const float* planes = &box.planes[0][0];
        const PlaneOffsets& at = *offsets_;
        __m256 t_near = _mm256_max_ps(distance(planes, at.near[2], near_origin_[2], inv_[2]), tmin_);
        t_near = _mm256_max_ps(distance(planes, at.near[1], near_origin_[1], inv_[1]), t_near);
        t_near = _mm256_max_ps(distance(planes, at.near[0], near_origin_[0], inv_[0]), t_near);
        __m256 t_far = _mm256_min_ps(distance(planes, at.far[2], far_origin_[2], far_inv_[2]), tmax);
        t_far = _mm256_min_ps(distance(planes, at.far[1], far_origin_[1], far_inv_[1]), t_far);
        t_far = _mm256_min_ps(distance(planes, at.far[0], far_origin_[0], far_inv_[0]), t_far);
        entry = t_near;
        return _mm256_movemask_ps(_mm256_cmp_ps(t_near, t_far, _CMP_LE_OQ));
    }

private:
    // Lane i of v in all eight lanes.
    static __m256 lane(__m128 v, int i) { return _mm256_permutevar8x32_ps(_mm256_castps128_ps256(v), _mm256_set1_epi32(i)); }
    // Distances to eight planes along one axis, `offset` bytes from the first plane.
    static __m256 distance(const float* planes, intptr_t offset, __m256 origin, __m256 inv) {
        const auto* plane = reinterpret_cast<const float*>(reinterpret_cast<const char*>(planes) + offset);
        return _mm256_mul_ps(_mm256_sub_ps(_mm256_load_ps(plane), origin), inv);
    }

    // Where an axis' near and far planes lie, in bytes from the first plane, for each octant of
    // the direction (bit a set: negative along axis a, which swaps that axis' planes). Read from
    // this table rather than set up per ray, and in bytes, so the loads need no scaling.
    struct PlaneOffsets {
        intptr_t near[3], far[3];
    };
    static constexpr std::array<PlaneOffsets, 8> kPlaneOffsets = [] {
        std::array<PlaneOffsets, 8> table{};
        for (int octant = 0; octant < 8; ++octant)
            for (int a = 0; a < 3; ++a) {
                const int flip = octant >> a & 1;
                table[octant].near[a] = intptr_t{sizeof(float)} * kBvhWidth * (2 * a + flip);
                table[octant].far[a] = intptr_t{sizeof(float)} * kBvhWidth * (2 * a + 1 - flip);
            }
        return table;
    }();

    __m256 near_origin_[3], far_origin_[3], inv_[3], far_inv_[3], tmin_;
    const PlaneOffsets* offsets_;
};

}  // namespace glint
