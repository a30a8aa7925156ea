#include "scene/scene.h"

#include "scene/bsdf.h"

namespace glint {
namespace {

// Each material as the lights and the strategies see it anywhere on its surface.
std::vector<Material> everywhere(const std::vector<Material>& materials, const std::vector<MaterialMaps>& maps) {
    std::vector<Material> out = materials;
    for (Material& m : out)
        if (m.maps != Material::kNoMaps) m = maps[m.maps].everywhere(m);
    return out;
}

// Each triangle's cut-out, from its material's alpha map: none at all when no material has one.
CutOuts cutouts(const Geometry& geometry, const std::vector<Material>& materials,
                const std::vector<uint32_t>& material_of_prim, const std::vector<MaterialMaps>& maps) {
    CutOuts out;
    std::vector<uint32_t> mask_of_material(materials.size(), CutOuts::kNoMask);
    for (size_t i = 0; i < materials.size(); ++i) {
        const uint32_t index = materials[i].maps;
        if (index == Material::kNoMaps || !maps[index].alpha.present()) continue;
        mask_of_material[i] = uint32_t(out.masks.size());
        out.masks.push_back(maps[index].alpha);
    }
    if (out.masks.empty()) return out;
    for (size_t t = 0; t < geometry.triangle_count(); ++t)
        out.mask_of_triangle.push_back(mask_of_material[material_of_prim[geometry.triangle_id(t)]]);
    return out;
}

}  // namespace

Scene::Scene(CameraSettings camera, Rgb background, IntegratorSettings integrator, SceneSurfaces surfaces)
    : camera_(camera),
      background_(background),
      integrator_(integrator),
      geometry_(std::move(surfaces.spheres), std::move(surfaces.triangles), integrator.accelerator),
      materials_(std::move(surfaces.materials)),
      material_of_prim_(std::move(surfaces.material_of_prim)),
      maps_(std::move(surfaces.maps)),
      textures_(std::move(surfaces.textures)),
      has_normals_(!surfaces.attributes.normals.empty()),
      lights_(geometry_, everywhere(materials_, maps_), material_of_prim_) {
    geometry_.attach(std::move(surfaces.attributes), cutouts(geometry_, materials_, material_of_prim_, maps_));
    for (const Material& m : everywhere(materials_, maps_)) flags_.push_back(Bsdf::flags(m));
}

Rgb Scene::emission_at(const Vec3& p, const LightSample& ls) const {
    SurfaceInteraction si;
    si.prim = ls.prim;
    if (geometry_.is_sphere(ls.prim)) {
        si.n = normalize(p + ls.wi * ls.distance - geometry_.sphere(ls.prim).centre);
    } else {
        si.b1 = ls.b1;
        si.b2 = ls.b2;
    }
    Material scratch;
    return material_at(si, scratch).emission;
}

}  // namespace glint
