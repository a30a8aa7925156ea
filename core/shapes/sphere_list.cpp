#include "shapes/sphere_list.h"

#include <immintrin.h>

#include <algorithm>
#include <iterator>
#include <limits>

namespace glint {
namespace {

struct Lanes {
    __m256d t;    // each lane's t (meaningful where it hits)
    __m256d hit;  // all ones in the lanes that hit in (tmin, tmax]
};

// Sphere::intersect on four spheres; see there for the algebra. `self` is all ones in the lane of
// the sphere the ray leaves, if it is one of these. A lane with a NaN radius never hits (its
// discriminant and roots are NaN, which no comparison accepts): groups are padded with those.
Lanes intersect(const Ray& ray, const double* cx, const double* cy, const double* cz, const double* radius,
                __m256d self) {
    const __m256d dx = _mm256_set1_pd(ray.d.x), dy = _mm256_set1_pd(ray.d.y), dz = _mm256_set1_pd(ray.d.z);
    const __m256d fx = _mm256_sub_pd(_mm256_set1_pd(ray.o.x), _mm256_load_pd(cx));
    const __m256d fy = _mm256_sub_pd(_mm256_set1_pd(ray.o.y), _mm256_load_pd(cy));
    const __m256d fz = _mm256_sub_pd(_mm256_set1_pd(ray.o.z), _mm256_load_pd(cz));
    const __m256d r = _mm256_load_pd(radius);
    auto dot4 = [](__m256d ax, __m256d ay, __m256d az, __m256d bx, __m256d by, __m256d bz) {
        return _mm256_add_pd(_mm256_add_pd(_mm256_mul_pd(ax, bx), _mm256_mul_pd(ay, by)), _mm256_mul_pd(az, bz));
    };
    const __m256d a = _mm256_set1_pd(dot(ray.d, ray.d));
    const __m256d b = dot4(fx, fy, fz, dx, dy, dz);
    const __m256d s = _mm256_div_pd(b, a);
    const __m256d gx = _mm256_sub_pd(fx, _mm256_mul_pd(dx, s)), gy = _mm256_sub_pd(fy, _mm256_mul_pd(dy, s)),
                  gz = _mm256_sub_pd(fz, _mm256_mul_pd(dz, s));
    const __m256d closest = _mm256_sqrt_pd(dot4(gx, gy, gz, gx, gy, gz));
    const __m256d disc = _mm256_mul_pd(_mm256_mul_pd(a, _mm256_sub_pd(r, closest)), _mm256_add_pd(r, closest));
    const __m256d sign = _mm256_set1_pd(-0.0);
    const __m256d root = _mm256_or_pd(_mm256_andnot_pd(sign, _mm256_sqrt_pd(disc)), _mm256_and_pd(sign, b));
    const __m256d q = _mm256_xor_pd(_mm256_add_pd(b, root), sign);
    const __m256d lf = _mm256_sqrt_pd(dot4(fx, fy, fz, fx, fy, fz));
    const __m256d c = _mm256_mul_pd(_mm256_sub_pd(lf, r), _mm256_add_pd(lf, r));
    const __m256d r0 = _mm256_div_pd(c, q), r1 = _mm256_div_pd(q, a);
    // std::min(r0, r1) is (r1 < r0 ? r1 : r0) and std::max(r0, r1) is (r0 < r1 ? r1 : r0):
    // the same operand order keeps signed zeros as the scalar test has them.
    const __m256d t_near = _mm256_min_pd(r1, r0), t_far = _mm256_max_pd(r1, r0);
    const __m256d tmin = _mm256_set1_pd(ray.tmin), zero = _mm256_setzero_pd();
    __m256d t = _mm256_blendv_pd(t_far, t_near, _mm256_cmp_pd(t_near, tmin, _CMP_GT_OQ));
    // Leaving this sphere: only the far root of a ray heading inside (b < 0) counts.
    t = _mm256_blendv_pd(t, t_far, self);
    const __m256d miss = _mm256_or_pd(_mm256_or_pd(_mm256_cmp_pd(disc, zero, _CMP_LT_OQ), _mm256_cmp_pd(q, zero, _CMP_EQ_OQ)),
                                      _mm256_and_pd(self, _mm256_cmp_pd(b, zero, _CMP_GE_OQ)));
    const __m256d in_range = _mm256_and_pd(_mm256_cmp_pd(t, tmin, _CMP_GT_OQ),
                                           _mm256_cmp_pd(t, _mm256_set1_pd(ray.tmax), _CMP_LE_OQ));
    return {t, _mm256_andnot_pd(miss, in_range)};
}

// All ones in the lanes whose sphere index (`ids`) is `index`.
__m256d lanes_of(__m256i ids, uint32_t index) {
    return _mm256_castsi256_pd(_mm256_cmpeq_epi64(ids, _mm256_set1_epi64x(int64_t{index})));
}

// The sphere indices of the first group's lanes, and the step to the next group's.
const __m256i kFirstIds = _mm256_setr_epi64x(0, 1, 2, 3);
const __m256i kGroupStep = _mm256_set1_epi64x(4);

// Of two (t, sphere) pairs per lane, the nearer, of equal t the higher sphere index: the order
// in which a scalar loop narrowing tmax with `<=` leaves its answer. A lane without a hit holds
// (tmax, -1), which every hit within tmax beats.
void keep_nearer(__m256d& t, __m256i& found, __m256d other_t, __m256i other_found) {
    const __m256d take = _mm256_or_pd(
        _mm256_cmp_pd(other_t, t, _CMP_LT_OQ),
        _mm256_and_pd(_mm256_cmp_pd(other_t, t, _CMP_EQ_OQ), _mm256_castsi256_pd(_mm256_cmpgt_epi64(other_found, found))));
    t = _mm256_blendv_pd(t, other_t, take);
    found = _mm256_castpd_si256(_mm256_blendv_pd(_mm256_castsi256_pd(found), _mm256_castsi256_pd(other_found), take));
}

}  // namespace

SphereList::SphereList(const std::vector<Sphere>& spheres) : groups_((spheres.size() + 3) / 4) {
    for (Group& g : groups_) std::fill(std::begin(g.radius), std::end(g.radius), std::numeric_limits<double>::quiet_NaN());
    for (size_t i = 0; i < spheres.size(); ++i) {
        Group& g = groups_[i / 4];
        g.cx[i % 4] = spheres[i].centre.x;
        g.cy[i % 4] = spheres[i].centre.y;
        g.cz[i % 4] = spheres[i].centre.z;
        g.radius[i % 4] = spheres[i].radius;
    }
}

// Each lane keeps the nearest hit among its spheres (of equal ones the later, as `<=` in index
// order decides) and which sphere that is; then the lanes are reduced pairwise in the same
// order: the scalar loop's answer, without a branch per hit.
int SphereList::closest(const Ray& ray, uint32_t self, double& t) const {
    __m256i ids = kFirstIds;
    __m256d nearest = _mm256_set1_pd(ray.tmax);
    __m256i found = _mm256_set1_epi64x(-1);
    for (const Group& group : groups_) {
        const Lanes lanes = intersect(ray, group.cx, group.cy, group.cz, group.radius, lanes_of(ids, self));
        const __m256d nearer = _mm256_and_pd(lanes.hit, _mm256_cmp_pd(lanes.t, nearest, _CMP_LE_OQ));
        nearest = _mm256_blendv_pd(nearest, lanes.t, nearer);
        found = _mm256_castpd_si256(_mm256_blendv_pd(_mm256_castsi256_pd(found), _mm256_castsi256_pd(ids), nearer));
        ids = _mm256_add_epi64(ids, kGroupStep);
    }
    // Lanes 0, 1 against 2, 3, then 0 against 1.
    keep_nearer(nearest, found, _mm256_permute2f128_pd(nearest, nearest, 1),
                _mm256_permute2f128_si256(found, found, 1));
    keep_nearer(nearest, found, _mm256_permute_pd(nearest, 0b0101),
                _mm256_castpd_si256(_mm256_permute_pd(_mm256_castsi256_pd(found), 0b0101)));
    t = _mm256_cvtsd_f64(nearest);
    return static_cast<int>(_mm256_extract_epi64(found, 0));
}

bool SphereList::any(const Ray& ray, uint32_t self, uint32_t target) const {
    __m256i ids = kFirstIds;
    for (const Group& group : groups_) {
        const Lanes lanes = intersect(ray, group.cx, group.cy, group.cz, group.radius, lanes_of(ids, self));
        if (_mm256_movemask_pd(_mm256_andnot_pd(lanes_of(ids, target), lanes.hit))) return true;
        ids = _mm256_add_epi64(ids, kGroupStep);
    }
    return false;
}

}  // namespace glint
