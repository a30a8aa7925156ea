#include "scene/scene.h"

namespace glint {

Scene::Scene(CameraSettings camera, Rgb background, IntegratorSettings integrator, std::vector<Sphere> spheres,
             std::vector<Triangle> triangles, std::vector<Material> materials, std::vector<uint32_t> material_of_prim)
    : camera_(camera),
      background_(background),
      integrator_(integrator),
      geometry_(std::move(spheres), std::move(triangles), integrator.accelerator),
      materials_(std::move(materials)),
      material_of_prim_(std::move(material_of_prim)),
      lights_(geometry_, materials_, material_of_prim_) {}

}  // namespace glint
