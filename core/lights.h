// Every emissive primitive is a light. Next-event estimation picks one in proportion to its
// power (area × luminance of its emission) and samples a point on it as seen from the shading
// point: spheres by the cone they subtend, triangles by area. A sphere light whose surface an
// opaque sphere cuts is seen only through the cap on the shading point's side of that sphere's
// surface; where that cap is smaller than the light's horizon, light sampling picks points on it
// by area instead (smallpt's light: a disc of radius 18 instead of a nearly full hemisphere of
// directions of which the ceiling hides 97%).
#pragma once

#include <vector>

#include "geometry.h"
#include "material.h"
#include "sphere_cap.h"

namespace glint {

struct LightSample {
    Vec3 wi;          // unit direction from the shading point to the light point
    double distance;  // along wi
    Rgb emission;
    double pdf;       // solid-angle density, including the choice of this light
    uint32_t prim;
};

class LightSet {
public:
    LightSet() = default;
    LightSet(const Geometry& geometry, const std::vector<Material>& materials,
             const std::vector<uint32_t>& material_of_prim);

    bool empty() const { return lights_.empty(); }
    size_t size() const { return lights_.size(); }

    // A light point as seen from p, which lies on primitive `self` (or kNoPrimitive); `facing`
    // is self's unit normal on the side p looks from (zero if unknown).
    bool sample(const Vec3& p, uint32_t self, double u_pick, double u1, double u2, LightSample& out,
                const Vec3& facing = Vec3{}) const;
    // The solid-angle density with which sample() would have produced `hit` seen from p.
    double pdf(const Vec3& p, uint32_t self, const SurfaceInteraction& hit, const Vec3& facing = Vec3{}) const;

private:
    struct Light {
        uint32_t prim;
        Rgb emission;
        uint32_t occluders_begin = 0, occluders_end = 0;  // into occluders_
    };
    // An opaque sphere whose surface cuts a sphere light, and the light's caps on either side.
    struct Occluder {
        uint32_t prim;
        SphereCap inside, outside;
    };
    // The smallest cap of the light that holds every point p can see, if smaller than the
    // light's horizon from p.
    bool visible_cap(const Vec3& p, uint32_t self, const Vec3& facing, const Light& light, SphereCap& cap) const;
    // Density of picking a point on the light by area, converted to solid angle at p.
    static double area_pdf_to_solid_angle(const Vec3& p, const Vec3& q, const Vec3& nq, double area);
    bool sees_as_cone(const Vec3& p, uint32_t self, uint32_t prim) const;
    double pick_probability(size_t light) const;

    const Geometry* geometry_ = nullptr;
    std::vector<Light> lights_;
    std::vector<Occluder> occluders_;
    std::vector<double> cdf_;                // cumulative power, normalised; cdf_.back() == 1
    std::vector<uint32_t> light_of_prim_;    // kNoLight where the primitive does not emit
    static constexpr uint32_t kNoLight = 0xFFFFFFFFu;
};

}  // namespace glint
