// Every emissive primitive is a light. Next-event estimation picks one in proportion to its
// power (area × luminance of its emission) and samples a point on it as seen from the shading
// point: spheres by the cone they subtend, triangles by area. A sphere light whose surface an
// opaque sphere cuts is seen only through the cap on the shading point's side of that sphere's
// surface; where that cap is smaller than the light's horizon, light sampling picks points on it
// by area instead (smallpt's light: a disc of radius 18 instead of a nearly full hemisphere of
// directions of which the ceiling hides 97%). An environment is one more light, sampled by its
// own distribution, its power that of its radiance falling on the scene's bounding sphere, and
// so is the sun, by its cone (or its one direction, a delta light).
#pragma once

#include <vector>

#include "scene/environment.h"
#include "scene/geometry.h"
#include "scene/point_light.h"
#include "scene/sun.h"
#include "scene/material.h"
#include "shapes/sphere_cap.h"

namespace glint {

struct LightSample {
    Vec3 wi;          // unit direction from the shading point to the light point
    double distance;  // along wi
    Rgb emission;
    double pdf;       // solid-angle density, including the choice of this light
    uint32_t prim;    // kNoPrimitive: the environment or the sun (distance infinite)
    bool delta = false;  // from a delta light, which no BSDF sample reaches: no MIS
    double b1 = 0, b2 = 0;  // on a triangle light, the point's barycentric weights of v1 and v2
};

// What lights a scene besides its emitters.
struct OtherLights {
    const Environment* environment = nullptr;
    const Sun* sun = nullptr;
    std::vector<PointLight> points;
};

class LightSet {
public:
    LightSet() = default;
    LightSet(const Geometry& geometry, const std::vector<Material>& materials,
             const std::vector<uint32_t>& material_of_prim, OtherLights others = {});

    bool empty() const { return cdf_.empty(); }
    const std::vector<PointLight>& point_lights() const { return points_; }
    size_t size() const { return cdf_.size(); }

    // A light point as seen from p, which lies on primitive `self` (or kNoPrimitive); `facing`
    // is self's unit normal on the side p looks from (zero if unknown). u1 both picks the light,
    // in proportion to its power, and places the point on it.
    bool sample(const Vec3& p, uint32_t self, double u1, double u2, LightSample& out,
                const Vec3& facing = Vec3{}) const;
    // The solid-angle density with which sample() would have produced `hit` seen from p.
    double pdf(const Vec3& p, uint32_t self, const SurfaceInteraction& hit, const Vec3& facing = Vec3{}) const;
    // The solid-angle density with which sample() would have produced direction d toward the
    // environment.
    double environment_pdf(const Vec3& d) const {
        return environment_ ? environment_->pdf(d) * pick_probability(environment_index_) : 0;
    }
    // The same toward the sun's disc.
    double sun_pdf(const Vec3& d) const { return sun_ ? sun_->pdf(d) * pick_probability(sun_index_) : 0; }

private:
    struct Light {
        uint32_t prim;
        Rgb emission;
        uint32_t caps_begin = 0, caps_end = 0;  // into caps_
    };
    // An opaque sphere whose surface cuts a sphere light, and the light's cap on one side of it:
    // from that side only the cap can be seen.
    struct OccludedCap {
        uint32_t occluder;
        bool inside;  // the side: inside the occluder or outside
        SphereCap cap;
    };
    // The smallest cap of the light that holds every point p can see, if smaller than the
    // light's horizon from p (p lies at distance `distance` from the light's centre).
    const SphereCap* visible_cap(const Vec3& p, uint32_t self, const Vec3& facing, const Light& light,
                                 double distance) const;
    // Density of picking a point on the light by area, converted to solid angle at p (q at
    // squared distance dist2, cos_light the cosine at q).
    static double area_pdf_to_solid_angle(double dist2, double cos_light, double area);
    static double area_pdf_to_solid_angle(const Vec3& p, const Vec3& q, const Vec3& nq, double area);
    // The same for a sampled point q (normal nq), whose direction and distance from p it puts in `out`.
    static double toward(const Vec3& p, const Vec3& q, const Vec3& nq, double area, LightSample& out);
    // The distance from p to the centre of sphere light `prim` if p sees it as a cone, else 0.
    double cone_distance(const Vec3& p, uint32_t self, uint32_t prim) const;
    double pick_probability(size_t light) const;
    static double bounding_radius(const Geometry& geometry);
    // Entry `index` of cdf_, one of the lights that are not emitters, sampled from p.
    [[gnu::noinline]] bool sample_other(const Vec3& p, size_t index, double u1, double u2, double share,
                                        LightSample& out) const;
    // The environment's or the sun's share: its direction, radiance and density into `out`.
    bool sample_environment(double u1, double u2, double share, LightSample& out) const;
    bool sample_sun(double u1, double u2, double share, LightSample& out) const;
    bool sample_point(const Vec3& p, const PointLight& light, double share, LightSample& out) const;

    const Geometry* geometry_ = nullptr;
    // When they shed light, each an entry of cdf_ after the emitters'.
    const Environment* environment_ = nullptr;
    const Sun* sun_ = nullptr;
    size_t environment_index_ = 0, sun_index_ = 0;
    std::vector<PointLight> points_;
    size_t points_index_ = 0;  // points_[i] is entry points_index_ + i of cdf_
    std::vector<Light> lights_;
    std::vector<OccludedCap> caps_;  // each light's, smallest first
    std::vector<double> cdf_;                // cumulative power, normalised; cdf_.back() == 1
    std::vector<uint32_t> light_of_prim_;    // kNoLight where the primitive does not emit
    static constexpr uint32_t kNoLight = 0xFFFFFFFFu;
};

}  // namespace glint
