// The slab test of one ray against eight boxes (half a BVH node's children) at once, in AVX single
// precision, made conservative: it never rejects a box that the exact test with the double ray
// would accept. Two implementations: RayBoxTest for every ray, and FusedRayBoxTest, a shorter
// chain of dependent instructions, for the rays of a render (see there).
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
#error "glint's BVH traversal needs AVX2 and FMA (CMakeLists.txt passes -mavx2 -mfma)"
#endif

#include <immintrin.h>

#include <array>
#include <cmath>
#include <cstdint>
#include <limits>

#include "base/float_rounding.h"
#include "base/ray.h"

namespace glint {

// Boxes per test: one AVX register of floats.
inline constexpr int kBoxLanes = 8;
// Far distances are scaled by this: above 1 + 2·gamma(4), with room for its own rounding.
inline constexpr float kFarPad = 1 + 0x1p-20f;

// Eight boxes in structure-of-arrays order: planes[2·axis] holds the eight lower bounds along
// that axis, planes[2·axis + 1] the eight upper ones. An unused slot has lo = +inf and hi = -inf,
// which no ray can enter.
struct alignas(32) WideBox {
    float planes[6][kBoxLanes];

    bool used(int slot) const { return planes[0][slot] <= planes[1][slot]; }
    // A used slot's box: half its surface area, in double.
    double half_area(int slot) const {
        const auto extent = [&](int a) { return double(planes[2 * a + 1][slot]) - planes[2 * a][slot]; };
        return extent(0) * extent(1) + extent(1) * extent(2) + extent(2) * extent(0);
    }
};

// Where an axis' near and far planes lie, in bytes from the first plane, for each octant of the
// direction (bit a set: negative along axis a, which swaps that axis' planes). Read from this
// table rather than set up per ray, and in bytes, so the loads need no scaling.
struct PlaneOffsets {
    intptr_t near[3], far[3];
};
inline constexpr std::array<PlaneOffsets, 8> kPlaneOffsets = [] {
    std::array<PlaneOffsets, 8> table{};
    for (int octant = 0; octant < 8; ++octant)
        for (int a = 0; a < 3; ++a) {
            const int flip = octant >> a & 1;
            table[octant].near[a] = intptr_t{sizeof(float)} * kBoxLanes * (2 * a + flip);
            table[octant].far[a] = intptr_t{sizeof(float)} * kBoxLanes * (2 * a + 1 - flip);
        }
    return table;
}();

// Lane i of v in all eight lanes.
inline __m256 broadcast_lane(__m128 v, int i) {
    return _mm256_permutevar8x32_ps(_mm256_castps128_ps256(v), _mm256_set1_epi32(i));
}

// Lanes x, y and z of four vectors, each in all eight lanes of its own register (`to[v][axis]`):
// a ray's per-axis values beside eight boxes' planes. Axis by axis, as the box tests read them.
[[gnu::always_inline]] inline void broadcast_axes(const __m128 (&from)[4], __m256* const (&to)[4]) {
    for (int a = 0; a < 3; ++a)
        for (int v = 0; v < 4; ++v) to[v][a] = broadcast_lane(from[v], a);
}

// Bytes `offset` on from the first plane of a box.
inline __m256 load_planes(const WideBox& box, intptr_t offset) {
    return _mm256_load_ps(reinterpret_cast<const float*>(reinterpret_cast<const char*>(&box) + offset));
}

// The slab test for every ray, as the header describes: the traversal uses it for the rays
// FusedRayBoxTest does not cover.
class RayBoxTest {
public:
    explicit RayBoxTest(const Ray& ray) {
        // Rounded four at a time: the origin up, the origin and tmin down, the reciprocals to
        // nearest. A negative reciprocal (-0's -inf included) swaps an axis' near and far
        // planes, so its sign bit picks the rounding for each: no branch per axis.
        const __m256d origin_tmin = _mm256_setr_pd(ray.o.x, ray.o.y, ray.o.z, ray.tmin);
        const __m128 up = to_float_up(origin_tmin), down = to_float_down(origin_tmin);
        const __m128 inv = _mm256_cvtpd_ps(_mm256_div_pd(_mm256_set1_pd(1.0), _mm256_setr_pd(ray.d.x, ray.d.y, ray.d.z, 1.0)));
        const __m128 far_inv = _mm_mul_ps(inv, _mm_set1_ps(kFarPad));
        const __m128 near = _mm_blendv_ps(up, down, inv), far = _mm_blendv_ps(down, up, inv);
        offsets_ = &kPlaneOffsets[_mm_movemask_ps(inv) & 7];
        broadcast_axes({near, far, inv, far_inv}, {near_origin_, far_origin_, inv_, far_inv_});
        tmin_ = broadcast_lane(down, 3);
    }

    // Bit i of the result is set when box i overlaps the ray in (tmin, tmax]; `entry` receives
    // the eight entry distances, none negative. `tmax` is the ray's limit rounded up to float,
    // in every lane.
    int hit(const WideBox& box, __m256 tmax, __m256& entry) const {
        const PlaneOffsets& at = *offsets_;
        __m256 t_near = _mm256_max_ps(distance(box, at.near[2], near_origin_[2], inv_[2]), tmin_);
        t_near = _mm256_max_ps(distance(box, at.near[1], near_origin_[1], inv_[1]), t_near);
        t_near = _mm256_max_ps(distance(box, at.near[0], near_origin_[0], inv_[0]), t_near);
        __m256 t_far = _mm256_min_ps(distance(box, at.far[2], far_origin_[2], far_inv_[2]), tmax);
        t_far = _mm256_min_ps(distance(box, at.far[1], far_origin_[1], far_inv_[1]), t_far);
        t_far = _mm256_min_ps(distance(box, at.far[0], far_origin_[0], far_inv_[0]), t_far);
        // A negative entry (a ray with tmin < 0) becomes +0, so that every entry's bits order
        // as the number does (see Bvh::store_keys); it only keeps more subtrees from being culled.
        entry = _mm256_max_ps(t_near, _mm256_setzero_ps());
        return _mm256_movemask_ps(_mm256_cmp_ps(t_near, t_far, _CMP_LE_OQ));
    }

private:
    // Distances to eight planes along one axis, `offset` bytes from the first plane.
    static __m256 distance(const WideBox& box, intptr_t offset, __m256 origin, __m256 inv) {
        return _mm256_mul_ps(_mm256_sub_ps(load_planes(box, offset), origin), inv);
    }

    __m256 near_origin_[3], far_origin_[3], inv_[3], far_inv_[3], tmin_;
    const PlaneOffsets* offsets_;
};

// The same test for the rays of a render, with a shorter latency: a node visit cannot begin
// before the box test of its parent ends, so the test's chain of dependent instructions sets the
// pace of the traversal. RayBoxTest's chain: a subtraction, a multiplication, three dependent
// float maxima and a compare; this one's: a fused multiply-subtract, two integer maxima (of
// one cycle each, against four) and an integer compare.
// - Each distance is plane·inv − o·inv in one fused multiply-subtract, with o·inv formed once
//   per ray and moved outward (up for near planes, down for far ones) beyond every rounding of
//   its own (outward()). What is left is the error analysis of RayBoxTest with one rounding
//   fewer: the reciprocal's and the fused operation's for a near distance, and the padding's
//   besides for a far one, which kFarPad covers.
// - Maxima and minima compare the distances' bits as signed integers: that is the order of
//   non-negative floats, and every negative float lies below every non-negative one. With
//   tmin >= +0 among its operands, the entry's maximum is the float maximum. The exit's minimum
//   is the float minimum when no operand is negative; otherwise it is negative, below the
//   entry, and the box is rejected, as it is by the exact test.
// - No NaN arises: the reciprocals are finite and nonzero, o·inv is finite, and a plane at
//   infinity (an unused slot) gives ±inf. (RayBoxTest absorbs its NaNs through VMAXPS's operand
//   order; x86's default NaN, negative as an integer, would reject the box here.)
// covers() admits a ray when tmin >= 0 and its direction and origin have ordinary magnitudes,
// as every ray of a render has unless it is exactly axis-parallel; the traversal gives the
// others to RayBoxTest.
class FusedRayBoxTest {
public:
    static bool covers(const Ray& ray) {
        // |d| in [2^-60, 2^60] and |o| <= 2^60 keep |o·inv| below 2^120 and every reciprocal a
        // normal float: no overflow in the set-up, and no product beyond float's range to round.
        const __m256d sign = _mm256_set1_pd(-0.0);
        const __m256d d = _mm256_andnot_pd(sign, _mm256_setr_pd(ray.d.x, ray.d.y, ray.d.z, 1.0));
        // Lane 3 holds 1, here and below, where it is unused: with a 0 GCC emitted a
        // register-to-register VMOVQ, which valgrind cannot decode, and with z repeated one
        // 32-byte load of the ray, which waits for the caller's narrower stores of it.
        const __m256d o = _mm256_andnot_pd(sign, _mm256_setr_pd(ray.o.x, ray.o.y, ray.o.z, 1.0));
        const __m256d in_range = _mm256_and_pd(_mm256_and_pd(_mm256_cmp_pd(d, _mm256_set1_pd(0x1p-60), _CMP_GE_OQ),
                                                             _mm256_cmp_pd(d, _mm256_set1_pd(0x1p60), _CMP_LE_OQ)),
                                               _mm256_cmp_pd(o, _mm256_set1_pd(0x1p60), _CMP_LE_OQ));
        return _mm256_movemask_pd(in_range) == 0xF && ray.tmin >= 0;
    }

    // Only for a ray that covers() accepts.
    explicit FusedRayBoxTest(const Ray& ray) {
        const __m256d inv_exact = _mm256_div_pd(_mm256_set1_pd(1.0), _mm256_setr_pd(ray.d.x, ray.d.y, ray.d.z, 1.0));
        const __m128 inv = _mm256_cvtpd_ps(inv_exact);
        const __m128 far_inv = _mm_mul_ps(inv, _mm_set1_ps(kFarPad));
        // o·inv and o·far_inv from the double reciprocal, moved outward (see outward()).
        const __m256d o_inv = _mm256_mul_pd(_mm256_setr_pd(ray.o.x, ray.o.y, ray.o.z, 1.0), inv_exact);
        const __m128 near_offset = outward(o_inv, 1.0);
        const __m128 far_offset = outward(_mm256_mul_pd(o_inv, _mm256_set1_pd(double{kFarPad})), -1.0);
        offsets_ = &kPlaneOffsets[_mm_movemask_ps(inv) & 7];
        broadcast_axes({inv, far_inv, near_offset, far_offset}, {inv_, far_inv_, near_offset_, far_offset_});
        // +0 for tmin = -0 too: the entry's maximum needs an operand that is not negative.
        tmin_ = _mm256_castps_si256(_mm256_set1_ps(ray.tmin > 0 ? to_float_down(ray.tmin) : 0.0f));
    }

    // As RayBoxTest::hit.
    int hit(const WideBox& box, __m256 tmax, __m256& entry) const {
        const PlaneOffsets& at = *offsets_;
        const __m256i t_near = max(max(distance(box, at.near[0], inv_[0], near_offset_[0]), distance(box, at.near[1], inv_[1], near_offset_[1])),
                                   max(distance(box, at.near[2], inv_[2], near_offset_[2]), tmin_));
        const __m256i t_far = min(min(distance(box, at.far[0], far_inv_[0], far_offset_[0]), distance(box, at.far[1], far_inv_[1], far_offset_[1])),
                                  min(distance(box, at.far[2], far_inv_[2], far_offset_[2]), _mm256_castps_si256(tmax)));
        entry = _mm256_castsi256_ps(t_near);
        return _mm256_movemask_ps(_mm256_castsi256_ps(_mm256_cmpgt_epi32(t_near, t_far))) ^ 0xFF;
    }

private:
    // The float to subtract from plane·inv (or plane·far_inv): v, the product o·inv in double
    // from the double reciprocal, moved in `direction` (+1 up for the near planes, -1 down for
    // the far ones) far enough to lie beyond the exact product with the float reciprocal the
    // test multiplies by. That product differs from v by the reciprocal's rounding to float and
    // the padding's (2^-24 each, relative) and by v's own rounding (2^-53); the float result is
    // rounded to nearest (2^-24): a step of 2^-22 covers them all. The absolute 2^-100 keeps a
    // zero origin coordinate (Sponza's camera has z = 0) off float's subnormals, which would
    // cost a microcode assist in every box test of the ray.
    static __m128 outward(__m256d v, double direction) {
        const __m256d magnitude = _mm256_andnot_pd(_mm256_set1_pd(-0.0), v);
        const __m256d step = _mm256_add_pd(_mm256_mul_pd(magnitude, _mm256_set1_pd(0x1p-22)), _mm256_set1_pd(0x1p-100));
        return _mm256_cvtpd_ps(_mm256_add_pd(v, _mm256_mul_pd(step, _mm256_set1_pd(direction))));
    }
    static __m256i distance(const WideBox& box, intptr_t offset, __m256 inv, __m256 offset_along) {
        return _mm256_castps_si256(_mm256_fmsub_ps(load_planes(box, offset), inv, offset_along));
    }
    static __m256i max(__m256i a, __m256i b) { return _mm256_max_epi32(a, b); }
    static __m256i min(__m256i a, __m256i b) { return _mm256_min_epi32(a, b); }

    __m256 inv_[3], far_inv_[3], near_offset_[3], far_offset_[3];
    __m256i tmin_;
    const PlaneOffsets* offsets_;
};

}  // namespace glint
