// What a render needs from a scene file: surfaces, their materials and lights, the camera,
// and how to integrate. Per-job choices (image size, samples, seed) live in RenderSettings.
#pragma once

#include <memory>
#include <optional>
#include <vector>

#include "scene/bsdf_flags.h"
#include "scene/camera.h"
#include "scene/geometry.h"
#include "scene/lights.h"
#include "scene/material.h"
#include "scene/material_maps.h"

namespace glint {

// Light tracing of caustics (see light_tracer.h). automatic: on when the scene has what it
// needs and pays for: a pinhole camera, a sphere light and a mirror or glass sphere it can reach.
enum class LightTracing { automatic, on, off };
enum class Guiding { automatic, on, off };

struct IntegratorSettings {
    bool light_sampling = true;  // next-event estimation with MIS; off gives smallpt's estimator
    int max_depth = 1024;        // surface hits per path, a hard cap; RR ends paths long before
    int rr_depth = 5;            // Russian roulette after this many hits, as smallpt
    Accelerator accelerator = Accelerator::automatic;
    LightTracing light_tracing = LightTracing::automatic;
    // Extra camera rays per sample for the direct view where it varies across a pixel
    // (direct_view.h); 0: the camera path always gathers it, as smallpt's does.
    int direct_view_rays = 8;
    // Path guiding (render/path_guide.h); automatic: where it pays (render/strategies.h).
    Guiding guiding = Guiding::automatic;
};

// The scene's surfaces: its primitives (spheres first, then triangles, as Geometry numbers them),
// what each is made of, and the textures its materials look up.
// The lights that are not emissive surfaces: from far away an environment and a sun, and
// point and spot lights.
struct SceneLights {
    std::shared_ptr<const Environment> environment;
    std::optional<SunSettings> sun;
    std::vector<PointLight> points;
};

struct SceneSurfaces {
    std::vector<Sphere> spheres;
    std::vector<Triangle> triangles;
    TriangleAttributes attributes;
    std::vector<Material> materials;
    std::vector<uint32_t> material_of_prim;
    std::vector<MaterialMaps> maps;  // Material::maps indexes these
    std::vector<std::shared_ptr<const Texture>> textures;  // what the maps look up
};

// Immutable once built (jobs share it across threads). Not copyable: the lights refer to the
// geometry.
class Scene {
public:
    // With an environment, film.background is only what camera rays and the mirror and glass
    // paths straight from the camera see where the environment is not visible to them.
    Scene(CameraSettings camera, Rgb background, IntegratorSettings integrator, SceneSurfaces surfaces,
          SceneLights lights = {});
    Scene(const Scene&) = delete;
    Scene& operator=(const Scene&) = delete;

    const CameraSettings& camera() const { return camera_; }
    const Rgb& background() const { return background_; }
    const IntegratorSettings& integrator() const { return integrator_; }
    const Geometry& geometry() const { return geometry_; }
    const LightSet& lights() const { return lights_; }
    const Environment* environment() const { return environment_.get(); }
    const Sun* sun() const { return sun_ ? &*sun_ : nullptr; }
    bool has_distant_lights() const { return environment_ || sun_; }
    // Primitive prim's material as the scene states it (a textured parameter: its scale).
    const Material& material(uint32_t prim) const { return materials_[material_of_prim_[prim]]; }
    // Its BSDF's flags, as the strategies choose by them: the same anywhere on the primitive
    // (MaterialMaps::everywhere), and a Lambertian under vertex normals or a normal map counted
    // as glossy, as its lobe is not the cosine about the geometric normal that light paths'
    // connections assume (render/mis.h).
    BsdfFlags flags(uint32_t prim) const {
        BsdfFlags f = flags_[material_of_prim_[prim]];
        if (has_normals_ && f.is_diffuse() && geometry_.smooth(prim)) f.bits |= BsdfFlags::glossy;
        return f;
    }
    // The material at si: material(si.prim), or with textures, `scratch` filled in with their values.
    const Material& material_at(const SurfaceInteraction& si, Material& scratch) const {
        const Material& m = material(si.prim);
        if (m.maps == Material::kNoMaps || !maps_[m.maps].shades()) return m;
        scratch = m;
        maps_[m.maps].apply(scratch, geometry_.uv(si));
        return scratch;
    }
    // The surface point `hit` along `ray`, its shading normal from its material's normal map if
    // it has one: what the integrator shades.
    SurfaceInteraction interaction(const Ray& ray, const Hit& hit) const {
        SurfaceInteraction si = geometry_.interaction(ray, hit);
        if (has_normal_maps_) map_normal(si);
        return si;
    }
    // Whether some emitter has maps (emission_at() then differs from the light's emission).
    bool has_textured_lights() const { return has_textured_lights_; }
    // The emission of the light point `ls` sampled from p, textured or not.
    Rgb emission_at(const Vec3& p, const LightSample& ls) const;
    const std::vector<std::shared_ptr<const Texture>>& textures() const { return textures_; }
    const std::vector<MaterialMaps>& maps() const { return maps_; }

private:
    CameraSettings camera_;
    Rgb background_;
    IntegratorSettings integrator_;
    Geometry geometry_;
    std::vector<Material> materials_;
    std::vector<uint32_t> material_of_prim_;
    std::vector<MaterialMaps> maps_;
    std::vector<std::shared_ptr<const Texture>> textures_;
    std::vector<BsdfFlags> flags_;  // per material
    bool has_normals_ = false;
    bool has_normal_maps_ = false;
    bool has_textured_lights_ = false;
    void map_normal(SurfaceInteraction& si) const;
    std::shared_ptr<const Environment> environment_;
    std::optional<Sun> sun_;
    LightSet lights_;
};

}  // namespace glint
