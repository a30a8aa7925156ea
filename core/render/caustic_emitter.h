// Where light tracing starts: rays leaving sphere lights toward mirror and glass spheres.
// Light tracing takes over exactly the paths camera → diffuse (one or more) → specular (one or
// more) → light whose last specular vertex is one of these spheres: caustics, which the path
// tracer finds only by chance. Such a path's light vertex can only be a point of the light that
// the specular sphere sees, so each (light, sphere) pair samples a point on a cap of the light
// that contains every such point, then a direction in the cone the sphere subtends from there.
//
// The cap is the smallest of: the light's horizon as seen from the sphere, and, for every
// opaque sphere whose surface cuts the light, the part of the light on the same side of that
// surface as the whole target sphere (the other part is hidden from it). smallpt's radius-600
// light pokes 0.27 units through its radius-1e5 ceiling: the cap is a disc of radius 18, not the
// nearly full hemisphere the light's cone spans.
//
// The sun (scene/sun.h) is a light of this kind too, with a pair for every mirror and glass
// sphere: a direction toward the sun as its light sampling picks one, then a point of the
// sphere's disc across that direction, from outside the scene. That covers every ray from the
// sun that meets the sphere. Its light paths are splatted at their first diffuse or glossy
// vertex only, which takes the sun's caustics (camera → y → specular+ → sun, the last specular
// vertex one of these spheres) from the path tracer; a delta sun's the path tracer cannot find
// at all.
#pragma once

#include <vector>

#include "scene/scene.h"
#include "shapes/sphere_cap.h"

namespace glint {

// The light in sun pairs (not a primitive).
inline constexpr uint32_t kSunLight = kNoPrimitive - 1;

struct EmittedRay {
    Ray ray;          // leaving the light's surface
    Rgb weight;       // emitted radiance · cos / (pdf of the point and direction)
    double emitted_ratio;  // cos / (pdf of the point and direction); unused for the sun
    uint32_t light;   // primitive, or kSunLight
};

class CausticEmitter {
public:
    CausticEmitter() = default;
    explicit CausticEmitter(const Scene& scene);

    bool empty() const { return pairs_.empty(); }
    // Whether any pair's light is a sphere (else all are the sun's).
    bool has_sphere_lights() const { return !pairs_.empty() && pairs_.front().light != kSunLight; }
    size_t pairs() const { return pairs_.size(); }

    bool sample(double u_pick, double u1, double u2, double u3, double u4, EmittedRay& out) const;
    // Whether sample() emits toward `target` from point x of light `light`, i.e. whether light
    // tracing covers a path whose last two vertices are x and `target`.
    bool covers(uint32_t light, const Vec3& x, uint32_t target) const;
    bool is_target(uint32_t light, uint32_t prim) const { return find(light, prim) != nullptr; }
    // Whether sample() emits from the sun toward `target`: whether light tracing covers a path
    // that leaves `target` for the sun.
    bool covers_sun(uint32_t target) const {
        return !pairs_.empty() && pairs_.back().light == kSunLight && find(kSunLight, target) != nullptr;
    }
    // Density (by area on the light, by solid angle at x) of emitting from point x of `light`
    // along d, as sample() would.
    double pdf(uint32_t light, const Vec3& x, const Vec3& d) const;

private:
    struct Pair {
        uint32_t light, target;
        SphereCap cap;  // on a sphere light
        Rgb emission;   // a sphere light's (the sun's is sampled with its direction)
        double far = 0;  // sun pairs: from the target's centre to outside the scene
    };
    static SphereCap cap_for(const Scene& scene, uint32_t light_prim, uint32_t target_prim);
    void add_sphere_light_pairs(const Scene& scene, std::vector<double>& flux);
    void add_sun_pairs(const Scene& scene, std::vector<double>& flux);
    bool sample_sun(const Pair& pair, double choice, double u1, double u2, double u3, double u4, EmittedRay& out) const;
    const Pair* find(uint32_t light, uint32_t target) const;
    // Density of emitting from x along d, summed over the pairs of `light` (`chosen`, if any,
    // is counted without testing).
    double pdf(uint32_t light, size_t chosen, const Vec3& x, const Vec3& d) const;
    static constexpr size_t kNone = ~size_t(0);

    const Geometry* geometry_ = nullptr;
    const Sun* sun_ = nullptr;
    std::vector<Pair> pairs_;    // grouped by light, the sun's last
    std::vector<double> cdf_;    // pair choice, by the flux the pair's target intercepts
};

}  // namespace glint
