#include "scene/scene.h"

#include "scene/bsdf.h"
#include "shapes/tangent_frames.h"

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

bool has_normal_map(const Material& m, const std::vector<MaterialMaps>& maps) {
    return m.maps != Material::kNoMaps && maps[m.maps].has(maps[m.maps].normal);
}

// The triangles' tangent frames, where some material has a normal map and the meshes UVs.
void add_tangents(const Geometry& geometry, TriangleAttributes& attributes) {
    std::vector<Triangle> triangles;
    for (size_t t = 0; t < geometry.triangle_count(); ++t) triangles.push_back(geometry.triangle(geometry.triangle_id(t)));
    attributes.tangents = tangent_frames(triangles, attributes.uvs, attributes.normals);
}

}  // namespace

Scene::Scene(CameraSettings camera, Rgb background, IntegratorSettings integrator, SceneSurfaces surfaces,
             SceneLights lights)
    : camera_(camera),
      background_(background),
      integrator_(integrator),
      geometry_(std::move(surfaces.spheres), std::move(surfaces.triangles), integrator.accelerator),
      materials_(std::move(surfaces.materials)),
      material_of_prim_(std::move(surfaces.material_of_prim)),
      maps_(std::move(surfaces.maps)),
      textures_(std::move(surfaces.textures)),
      has_normals_(!surfaces.attributes.normals.empty()),
      environment_(std::move(lights.environment)),
      sun_(lights.sun ? std::optional<Sun>(Sun(*lights.sun)) : std::nullopt),
      lights_(geometry_, everywhere(materials_, maps_), material_of_prim_,
              {environment_.get(), sun(), std::move(lights.points)}) {
    for (const Material& m : materials_) {
        has_normal_maps_ |= has_normal_map(m, maps_);
        has_textured_lights_ |= m.maps != Material::kNoMaps && (m.is_emissive() || maps_[m.maps].has(maps_[m.maps].emission));
    }
    if (has_normal_maps_ && !surfaces.attributes.uvs.empty()) add_tangents(geometry_, surfaces.attributes);
    geometry_.attach(std::move(surfaces.attributes), cutouts(geometry_, materials_, material_of_prim_, maps_));
    for (const Material& m : everywhere(materials_, maps_)) {
        BsdfFlags f = Bsdf::flags(m);
        if (f.is_diffuse() && has_normal_map(m, maps_)) f.bits |= BsdfFlags::glossy;
        flags_.push_back(f);
    }
}

void Scene::map_normal(SurfaceInteraction& si) const {
    const Material& m = material(si.prim);
    Vec3 tangent;
    double sign;
    if (!has_normal_map(m, maps_) || !geometry_.tangent(si, tangent, sign)) return;
    const MaterialMaps& maps = maps_[m.maps];
    const Uv uv = geometry_.uv(si);
    const Rgb c = maps.normal.rgb(uv.u, uv.v);
    const Vec3 n = si.shading_normal(), t = tangent - n * dot(n, tangent);
    const Vec3 mapped = t * ((2 * c.x - 1) * maps.normal_strength / length(t)) +
                        cross(n, t) * ((2 * c.y - 1) * maps.normal_strength * sign / length(t)) + n * (2 * c.z - 1);
    const double l = length(mapped);
    if (!(l > 0) || !std::isfinite(l)) return;
    si.ns = dot(mapped, si.n) < 0 ? -mapped / l : mapped / l;
    si.shaded = true;
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
