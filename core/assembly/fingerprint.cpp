#include "assembly/fingerprint.h"

#include "render/strategies.h"

namespace glint {
namespace {

void lookup(Fnv1a& h, const Scene& scene, const TextureLookup& t) {
    size_t index = 0;
    while (index < scene.textures().size() && scene.textures()[index].get() != t.texture) ++index;
    h.value(index);
    h.vec(t.scale);
    for (double v : {t.uv_scale[0], t.uv_scale[1], t.uv_offset[0], t.uv_offset[1]}) h.value(v);
    h.value(t.colorspace);
    h.value(t.channel);
}

// UVs, vertex normals, textures and what the materials look up in them: nothing for a scene
// without, so that its fingerprint stays what it was before glint read them.
void surface_maps(Fnv1a& h, const Scene& scene) {
    const TriangleAttributes& a = scene.geometry().attributes();
    h.bytes(a.uvs.data(), a.uvs.size() * sizeof(TriangleUvs));
    h.bytes(a.normals.data(), a.normals.size() * sizeof(TriangleNormals));
    for (const auto& t : scene.textures()) {
        for (int v : {t->width(), t->height(), t->channels()}) h.value(v);
        h.bytes(t->bytes().data(), t->bytes().size());
        h.bytes(t->floats().data(), t->floats().size_bytes());
    }
    for (const MaterialMaps& m : scene.maps()) {
        for (const TextureLookup* t : {&m.albedo, &m.roughness, &m.metallic, &m.emission, &m.alpha.alpha, &m.normal})
            lookup(h, scene, *t);
        h.value(m.alpha.cutoff);
        h.value(m.normal_strength);
    }
}

// Nothing for a scene without an environment, a sun or point lights, whose fingerprint stays
// what it was.
void other_lights(Fnv1a& h, const Scene& scene) {
    for (const PointLight& p : scene.lights().point_lights()) {
        for (const Vec3& v : {p.position, p.intensity, p.direction}) h.vec(v);
        for (double v : {p.cos_inner, p.cos_outer}) h.value(v);
        h.value(p.spot);
    }
    if (const Sun* sun = scene.sun()) {
        h.vec(sun->settings().direction);
        h.vec(sun->settings().irradiance);
        h.value(sun->settings().angle);
    }
    const Environment* env = scene.environment();
    if (!env) return;
    for (int v : {env->map().width(), env->map().height()}) h.value(v);
    h.bytes(env->map().texels().data(), env->map().texels().size_bytes());
    h.value(env->settings().strength);
    h.value(env->settings().rotation);
    h.value(env->settings().visible);
}

}  // namespace

uint64_t fingerprint(const Scene& scene, const RenderSettings& settings) {
    Fnv1a h;
    const CameraSettings& c = scene.camera();
    for (const Vec3& v : {c.position, c.direction, c.up, scene.background()}) h.vec(v);
    for (double v : {c.fov_degrees, c.near, c.aperture, c.focus_distance}) h.value(v);
    const IntegratorSettings& in = scene.integrator();
    h.value(in.light_sampling);
    h.value(in.max_depth);
    h.value(in.rr_depth);
    h.value(in.direct_view_rays);
    const Strategies strategies(scene);
    h.value(strategies.light_tracing());
    h.value(strategies.guiding());
    const Geometry& g = scene.geometry();
    h.value(g.accelerator());  // the accelerators may break exact ties between equal hits differently
    for (uint32_t prim = 0; prim < g.primitive_count(); ++prim) {
        if (g.is_sphere(prim)) {
            h.vec(g.sphere(prim).centre);
            h.value(g.sphere(prim).radius);
        } else {
            for (const Vec3& v : {g.triangle(prim).v0, g.triangle(prim).v1, g.triangle(prim).v2}) h.vec(v);
        }
        const Material& m = scene.material(prim);
        h.value(m.type);
        h.vec(m.albedo);
        h.value(m.ior);
        h.vec(m.emission);
        // Left out at their defaults, so that smallpt's materials keep their fingerprints.
        if (m.roughness != 0 || m.metallic != 0 || m.fresnel != FresnelModel::schlick) {
            h.value(m.roughness);
            h.value(m.metallic);
            h.value(m.fresnel);
        }
        if (m.maps != Material::kNoMaps) h.value(m.maps);
    }
    surface_maps(h, scene);
    other_lights(h, scene);
    h.value(settings.width);
    h.value(settings.height);
    h.value(settings.filter);
    h.value(settings.sampler);
    h.value(settings.seed);
    if (settings.aovs) h.value(settings.aovs);  // so that films without AOVs keep their fingerprints
    if (!settings.whole_image())  // so that films of whole renders keep their fingerprints
        for (int v : {settings.region.x0, settings.region.y0, settings.region.x1, settings.region.y1}) h.value(v);
    // Which pixels get samples, so the sums; left out when off, as region is when whole.
    if (settings.adaptive.on()) {
        h.value(settings.adaptive.threshold);
        h.value(settings.adaptive.min_spp);
        h.value(settings.adaptive.job_spp);
    }
    return h.digest();
}

}  // namespace glint
