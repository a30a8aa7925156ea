// What a render needs from a scene file: surfaces, their materials and lights, the camera,
// and how to integrate. Per-job choices (image size, samples, seed) live in RenderSettings.
#pragma once

#include <vector>

#include "scene/camera.h"
#include "scene/geometry.h"
#include "scene/lights.h"
#include "scene/material.h"

namespace glint {

// Light tracing of caustics (see light_tracer.h). automatic: on when the scene has what it
// needs and pays for: a pinhole camera, a sphere light and a mirror or glass sphere it can reach.
enum class LightTracing { automatic, on, off };

struct IntegratorSettings {
    bool light_sampling = true;  // next-event estimation with MIS; off gives smallpt's estimator
    int max_depth = 1024;        // surface hits per path, a hard cap; RR ends paths long before
    int rr_depth = 5;            // Russian roulette after this many hits, as smallpt
    Accelerator accelerator = Accelerator::automatic;
    LightTracing light_tracing = LightTracing::automatic;
    // Extra camera rays per sample for the direct view where it varies across a pixel
    // (direct_view.h); 0: the camera path always gathers it, as smallpt's does.
    int direct_view_rays = 8;
};

// Immutable once built (jobs share it across threads). Not copyable: the lights refer to the
// geometry.
class Scene {
public:
    Scene(CameraSettings camera, Rgb background, IntegratorSettings integrator, std::vector<Sphere> spheres,
          std::vector<Triangle> triangles, std::vector<Material> materials, std::vector<uint32_t> material_of_prim);
    Scene(const Scene&) = delete;
    Scene& operator=(const Scene&) = delete;

    const CameraSettings& camera() const { return camera_; }
    const Rgb& background() const { return background_; }
    const IntegratorSettings& integrator() const { return integrator_; }
    const Geometry& geometry() const { return geometry_; }
    const LightSet& lights() const { return lights_; }
    const Material& material(uint32_t prim) const { return materials_[material_of_prim_[prim]]; }

private:
    CameraSettings camera_;
    Rgb background_;
    IntegratorSettings integrator_;
    Geometry geometry_;
    std::vector<Material> materials_;
    std::vector<uint32_t> material_of_prim_;
    LightSet lights_;
};

}  // namespace glint
