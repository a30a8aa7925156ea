#include "sphere_list.h"

#include <immintrin.h>

namespace glint {
namespace {

struct Lanes {
    __m256d t;     // each lane's t (meaningful where it hits)
    unsigned hit;  // lanes that hit in (tmin, tmax]
};

// Sphere::intersect on four spheres; see there for the algebra. `self_lane` is the lane of the
// sphere the ray leaves (-1: none here), `valid` the lanes holding spheres.
Lanes intersect(const Ray& ray, const double* cx, const double* cy, const double* cz, const double* radius,
                int self_lane, unsigned valid) {
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
    const __m256d tmin = _mm256_set1_pd(ray.tmin);
    __m256d t = _mm256_blendv_pd(t_far, t_near, _mm256_cmp_pd(t_near, tmin, _CMP_GT_OQ));
    unsigned hit = valid & ~unsigned(_mm256_movemask_pd(_mm256_cmp_pd(disc, _mm256_setzero_pd(), _CMP_LT_OQ))) &
                   ~unsigned(_mm256_movemask_pd(_mm256_cmp_pd(q, _mm256_setzero_pd(), _CMP_EQ_OQ)));
    if (self_lane >= 0) {
        // Leaving this sphere: only the far root of a ray heading inside (b < 0) counts.
        const double b_self = b[self_lane];
        if (b_self >= 0) hit &= ~(1u << self_lane);
        t[self_lane] = t_far[self_lane];
    }
    const __m256d in_range = _mm256_and_pd(_mm256_cmp_pd(t, tmin, _CMP_GT_OQ),
                                           _mm256_cmp_pd(t, _mm256_set1_pd(ray.tmax), _CMP_LE_OQ));
    return {t, hit & unsigned(_mm256_movemask_pd(in_range))};
}

}  // namespace

SphereList::SphereList(const std::vector<Sphere>& spheres)
    : groups_((spheres.size() + 3) / 4), count_(static_cast<uint32_t>(spheres.size())) {
    for (size_t i = 0; i < spheres.size(); ++i) {
        Group& g = groups_[i / 4];
        g.cx[i % 4] = spheres[i].centre.x;
        g.cy[i % 4] = spheres[i].centre.y;
        g.cz[i % 4] = spheres[i].centre.z;
        g.radius[i % 4] = spheres[i].radius;
    }
}

namespace {

unsigned lanes_in(uint32_t count, size_t group) {
    const size_t left = count - 4 * group;
    return left >= 4 ? 0xFu : (1u << left) - 1;
}

int lane_of(uint32_t index, size_t group) {
    return index / 4 == group ? int(index % 4) : -1;
}

}  // namespace

int SphereList::closest(const Ray& ray, uint32_t self, double& t) const {
    int found = -1;
    double nearest = ray.tmax;
    for (size_t g = 0; g < groups_.size(); ++g) {
        const Group& group = groups_[g];
        const Lanes lanes = intersect(ray, group.cx, group.cy, group.cz, group.radius, lane_of(self, g), lanes_in(count_, g));
        for (unsigned m = lanes.hit; m != 0; m &= m - 1) {
            const int lane = __builtin_ctz(m);
            if (lanes.t[lane] <= nearest) {
                nearest = lanes.t[lane];
                found = int(4 * g) + lane;
            }
        }
    }
    t = nearest;
    return found;
}

bool SphereList::any(const Ray& ray, uint32_t self, uint32_t target) const {
    for (size_t g = 0; g < groups_.size(); ++g) {
        const Group& group = groups_[g];
        unsigned valid = lanes_in(count_, g);
        if (const int lane = lane_of(target, g); lane >= 0) valid &= ~(1u << lane);
        if (intersect(ray, group.cx, group.cy, group.cz, group.radius, lane_of(self, g), valid).hit) return true;
    }
    return false;
}

}  // namespace glint
