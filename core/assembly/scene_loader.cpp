#include "assembly/scene_loader.h"

#include <nlohmann/json.hpp>

#include <initializer_list>
#include <map>
#include <utility>

#include "base/files.h"
#include "io/json_text.h"
#include "io/obj_loader.h"
#include "io/texture_file.h"

namespace glint {
namespace {

using nlohmann::json;

// A JSON value and the path that leads to it, for error messages.
struct At {
    const json& value;
    std::string path;

    [[noreturn]] void fail(const std::string& message) const { throw SceneError(path, message); }
    bool has(const char* key) const { return value.contains(key); }
    At operator[](const char* key) const { return {value.at(key), path.empty() ? key : path + "." + key}; }
    At item(size_t i) const { return {value.at(i), path + "[" + std::to_string(i) + "]"}; }

    // An object holding only the named keys (a misspelt key must never pass silently).
    void expect_object(std::initializer_list<const char*> allowed) const {
        if (!value.is_object()) fail("must be an object");
        for (const auto& item : value.items()) {
            bool known = false;
            for (const char* key : allowed) known |= item.key() == key;
            if (known) continue;
            std::string list;
            for (const char* key : allowed) list += std::string(list.empty() ? "" : ", ") + key;
            throw SceneError(path.empty() ? item.key() : path + "." + item.key(), "unknown field (expected one of: " + list + ")");
        }
    }
    double number() const {
        if (!value.is_number()) fail("must be a number");
        const double v = value.get<double>();
        if (!std::isfinite(v)) fail("must be finite");
        return v;
    }
    double number_in(double lo, double hi) const {
        const double v = number();
        if (v < lo || v > hi) fail("must be in [" + format(lo) + ", " + format(hi) + "]");
        return v;
    }
    double positive(double hi) const {
        const double v = number();
        if (!(v > 0)) fail("must be > 0");
        if (v > hi) fail("must be <= " + format(hi));
        return v;
    }
    int64_t integer(int64_t lo, int64_t hi) const {
        if (!value.is_number_integer()) fail("must be an integer");
        const int64_t v = value.is_number_unsigned() && value.get<uint64_t>() > uint64_t(INT64_MAX)
                              ? INT64_MAX
                              : value.get<int64_t>();
        if (v < lo || v > hi) fail("must be in [" + std::to_string(lo) + ", " + std::to_string(hi) + "]");
        return v;
    }
    bool boolean() const {
        if (!value.is_boolean()) fail("must be true or false");
        return value.get<bool>();
    }
    std::string choice(std::initializer_list<const char*> options) const {
        std::string list;
        for (const char* o : options) list += std::string(list.empty() ? "" : ", ") + "\"" + o + "\"";
        if (!value.is_string()) fail("must be one of " + list);
        const std::string s = value.get<std::string>();
        for (const char* o : options)
            if (s == o) return s;
        fail("must be one of " + list + " (got \"" + s + "\")");
    }
    Vec3 vec3(double max_abs) const {
        if (!value.is_array() || value.size() != 3) fail("must be an array of 3 numbers");
        return {item(0).number_in(-max_abs, max_abs), item(1).number_in(-max_abs, max_abs),
                item(2).number_in(-max_abs, max_abs)};
    }
    // A colour: one number for grey, or [r, g, b]; each component in [0, max].
    Rgb colour(double max) const {
        if (value.is_number()) return Rgb{number_in(0, max)};
        if (!value.is_array() || value.size() != 3) fail("must be a number or an array of 3 numbers");
        return {item(0).number_in(0, max), item(1).number_in(0, max), item(2).number_in(0, max)};
    }

    static std::string format(double v) {
        std::ostringstream out;
        out << v;
        return out.str();
    }
};

constexpr double kMaxEmission = 1e12;

// A unit vector along v, exact in direction even where |v|² would underflow (1e-200 components):
// dividing by the largest component first keeps the squares in range.
Vec3 unit_direction(const At& at, const Vec3& v, const char* what) {
    const double largest = max_component(abs(v));
    if (!(largest > 0)) at.fail(what);
    return normalize(v / largest);
}

// Runs parse(); with whole-field errors, a SceneError it throws becomes `whole`, everything the
// value must be, at the value's own path.
template <typename F>
auto whole_field(const At& at, FieldErrors errors, const std::string& whole, F&& parse) -> decltype(parse()) {
    if (errors == FieldErrors::at_fault) return parse();
    try {
        return parse();
    } catch (const SceneError&) {
        at.fail(whole);
    }
}

// [x0, y0, x1, y1]: pixels, rows from the top; check_region() checks it against the size.
Region region_of(const At& at, const SceneLimits& limits, FieldErrors errors) {
    const std::string whole =
        "must be an array [x0, y0, x1, y1] of 4 integers in [0, " + std::to_string(limits.max_dimension) + "]";
    return whole_field(at, errors, whole, [&] {
        if (!at.value.is_array() || at.value.size() != 4) at.fail("must be an array [x0, y0, x1, y1] of 4 integers");
        int v[4];
        for (size_t i = 0; i < 4; ++i) v[i] = int(at.item(i).integer(0, limits.max_dimension));
        return Region{v[0], v[1], v[2], v[3]};
    });
}

// {"threshold": T, "min_spp": N}: the fields given, into `o`; check_settings() bounds the threshold.
void adaptive_fields(const At& at, const SceneLimits& limits, FieldErrors errors, FilmOverrides& o) {
    whole_field(at, errors, "must be an object {\"threshold\": T, \"min_spp\": N}", [&] {
        if (!at.value.is_object()) at.fail("must be an object");
    });
    at.expect_object({"threshold", "min_spp"});
    if (at.has("threshold")) o.adaptive_threshold = at["threshold"].number();
    if (!at.has("min_spp")) return;
    const At min_spp = at["min_spp"];
    const IntegerRange range = adaptive_min_spp_range(limits);
    o.adaptive_min_spp = uint32_t(whole_field(min_spp, errors, "must be an integer in " + range.text() + " (0: automatic)",
                                              [&] { return min_spp.integer(range.min, range.max); }));
}

class SceneParser {
public:
    SceneParser(const std::filesystem::path& folder, const SceneLimits& limits, AssetCache* assets)
        : folder_(folder), limits_(limits), assets_(assets) {}

    LoadedScene parse(const At& root) {
        root.expect_object({"description", "camera", "film", "integrator", "objects", "environment", "sun"});
        if (root.has("description") && !root["description"].value.is_string())
            root["description"].fail("must be a string");
        LoadedScene loaded;
        const CameraSettings camera = root.has("camera") ? parse_camera(root["camera"]) : CameraSettings{};
        Rgb background{0};
        if (root.has("film")) loaded.settings = parse_film(root["film"], background);
        check_settings(loaded.settings, limits_);
        const IntegratorSettings integrator = root.has("integrator") ? parse_integrator(root["integrator"]) : IntegratorSettings{};
        if (integrator.light_tracing == LightTracing::on && camera.aperture > 0)
            root["integrator"]["light_tracing"].fail("\"on\" needs a pinhole camera (camera.aperture 0)");
        if (root.has("objects")) parse_objects(root["objects"]);
        SceneLights distant;
        if (root.has("environment")) distant.environment = parse_environment(root["environment"]);
        if (root.has("sun")) distant.sun = parse_sun(root["sun"]);
        distant.points = std::move(point_lights_);
        loaded.scene = std::make_shared<const Scene>(camera, background, integrator, std::move(surfaces_),
                                                     std::move(distant));
        loaded.warnings = std::move(warnings_);
        return loaded;
    }

private:
    CameraSettings parse_camera(const At& at) const {
        at.expect_object({"position", "look_at", "direction", "up", "fov", "near", "aperture", "focus_distance"});
        const double range = limits_.max_coordinate;
        CameraSettings c;
        if (at.has("position")) c.position = at["position"].vec3(range);
        if (at.has("look_at") && at.has("direction")) at.fail("give either look_at or direction, not both");
        std::optional<double> look_distance;
        if (at.has("look_at")) {
            const Vec3 to = at["look_at"].vec3(range) - c.position;
            c.direction = unit_direction(at["look_at"], to, "must differ from position");
            look_distance = length(to);
        }
        if (at.has("direction")) c.direction = unit_direction(at["direction"], at["direction"].vec3(range), "must not be zero");
        if (at.has("up")) c.up = unit_direction(at["up"], at["up"].vec3(range), "must not be zero");
        if (!(length(cross(c.direction, c.up)) > 1e-9)) at.fail("up must not be parallel to the view direction");
        if (at.has("fov")) {
            c.fov_degrees = at["fov"].number();
            if (!(c.fov_degrees > 0 && c.fov_degrees < 180)) at["fov"].fail("must be in (0, 180) degrees");
        }
        if (at.has("near")) c.near = at["near"].number_in(0, range);
        if (at.has("aperture")) c.aperture = at["aperture"].number_in(0, range);
        c.focus_distance = look_distance.value_or(1);
        if (at.has("focus_distance")) c.focus_distance = at["focus_distance"].positive(range);
        return c;
    }

    RenderSettings parse_film(const At& at, Rgb& background) const {
        at.expect_object({"width", "height", "spp", "filter", "sampler", "background", "encoding", "seed", "time_limit",
                          "target_error", "region", "aovs", "adaptive"});
        RenderSettings s;
        if (at.has("width")) s.width = int(film_integer(at, FilmInteger::width));
        if (at.has("height")) s.height = int(film_integer(at, FilmInteger::height));
        if (at.has("spp")) s.spp = uint32_t(film_integer(at, FilmInteger::spp));
        if (at.has("filter")) s.filter = at["filter"].choice({"tent", "box"}) == "tent" ? Filter::tent : Filter::box;
        if (at.has("sampler"))
            s.sampler = at["sampler"].choice({"sobol", "independent"}) == "sobol" ? Sampler::sobol : Sampler::independent;
        if (at.has("background")) background = at["background"].colour(kMaxEmission);
        if (at.has("encoding"))
            s.encoding = encoding_named(at["encoding"].choice({"gamma2.2", "srgb"}));
        if (at.has("seed")) s.seed = uint64_t(film_integer(at, FilmInteger::seed));
        // Checked with the rest by check_settings(), as the command line's and a request's are.
        if (at.has("time_limit")) s.time_limit = at["time_limit"].number();
        if (at.has("target_error")) s.target_error = at["target_error"].number();
        if (at.has("region")) s.region = region_of(at["region"], limits_, FieldErrors::at_fault);
        if (at.has("aovs")) s.aovs = at["aovs"].boolean();
        if (at.has("adaptive")) s.adaptive = adaptive(at["adaptive"]);
        return s;
    }

    AdaptiveSettings adaptive(const At& at) const {
        FilmOverrides given;
        adaptive_fields(at, limits_, FieldErrors::at_fault, given);
        AdaptiveSettings a;
        a.threshold = given.adaptive_threshold.value_or(a.threshold);
        a.min_spp = given.adaptive_min_spp.value_or(a.min_spp);
        return a;
    }

    int64_t film_integer(const At& film, FilmInteger field) const {
        const IntegerRange range = film_range(field, limits_);
        return film[film_key(field)].integer(range.min, range.max);
    }

    static IntegratorSettings parse_integrator(const At& at) {
        at.expect_object(
            {"light_sampling", "light_tracing", "max_depth", "rr_depth", "accelerator", "direct_view_rays", "guiding"});
        IntegratorSettings s;
        if (at.has("light_sampling")) s.light_sampling = at["light_sampling"].boolean();
        if (at.has("max_depth")) s.max_depth = int(at["max_depth"].integer(1, 100000));
        if (at.has("rr_depth")) s.rr_depth = int(at["rr_depth"].integer(0, 100000));
        if (at.has("direct_view_rays")) s.direct_view_rays = int(at["direct_view_rays"].integer(0, 64));
        if (at.has("accelerator")) {
            const std::string a = at["accelerator"].choice({"auto", "bvh", "list"});
            s.accelerator = a == "auto" ? Accelerator::automatic : a == "bvh" ? Accelerator::bvh : Accelerator::list;
        }
        if (at.has("light_tracing")) s.light_tracing = automatic_on_off<LightTracing>(at["light_tracing"]);
        if (at.has("guiding")) s.guiding = automatic_on_off<Guiding>(at["guiding"]);
        return s;
    }

    // "auto", "on" or "off", as an enum with those three values.
    template <class Choice>
    static Choice automatic_on_off(const At& at) {
        const std::string t = at.choice({"auto", "on", "off"});
        return t == "auto" ? Choice::automatic : t == "on" ? Choice::on : Choice::off;
    }

    void parse_objects(const At& at) {
        if (!at.value.is_array()) at.fail("must be an array");
        if (at.value.size() > limits_.max_objects)
            at.fail("too many objects (limit " + std::to_string(limits_.max_objects) + ")");
        for (size_t i = 0; i < at.value.size(); ++i) {
            const At object = at.item(i);
            if (!object.value.is_object()) object.fail("must be an object");
            if (!object.has("type")) object.fail("needs a \"type\": \"sphere\", \"mesh\", \"point_light\" or \"spot_light\"");
            const std::string type = object["type"].choice({"sphere", "mesh", "point_light", "spot_light"});
            if (type == "sphere") parse_sphere(object);
            else if (type == "mesh") parse_mesh(object);
            else point_lights_.push_back(parse_point_light(object, type == "spot_light"));
        }
        // Spheres come first in the primitive numbering (see Geometry).
        std::vector<uint32_t>& of_prim = surfaces_.material_of_prim;
        of_prim.insert(of_prim.begin(), sphere_materials_.begin(), sphere_materials_.end());
    }

    static MaterialType material_type(const At& at) {
        return material_type_named(at.choice({"diffuse", "mirror", "glass", "metal", "plastic"}).c_str());
    }

    // The fields `at` gives, over `m`. A new type brings its own defaults (material.h) for the
    // fields not given with it; each field must be one the type has. A colour or number may be
    // a texture ({"texture": file, ...}), which gives the material maps of its own.
    Material material_fields(const At& at, Material m, bool with_emission) {
        if (with_emission)
            at.expect_object({"type", "albedo", "ior", "roughness", "metallic", "fresnel", "alpha", "alpha_cutoff", "normal_map", "emission"});
        else at.expect_object({"type", "albedo", "ior", "roughness", "metallic", "fresnel", "alpha", "alpha_cutoff", "normal_map"});
        if (at.has("type")) {
            const MaterialType type = material_type(at["type"]);
            if (type != m.type) m = with_type(m, type);
        }
        MaterialMaps maps = m.maps == Material::kNoMaps ? MaterialMaps{} : surfaces_.maps[m.maps];
        // Albedo above 1 would create energy.
        if (at.has("albedo")) m.albedo = colour_or_texture(at["albedo"], 1, maps.albedo);
        if (at.has("ior")) m.ior = field_of(at, "ior", has_ior(m.type), "only glass and plastic have an index of refraction").number_in(1e-3, 1e3);
        if (at.has("roughness"))
            m.roughness = number_or_texture(field_of(at, "roughness", has_roughness(m.type), "a diffuse material has no roughness"), maps.roughness);
        if (at.has("metallic"))
            m.metallic = number_or_texture(field_of(at, "metallic", has_metallic(m.type), "only metal and plastic have a metallic mix"), maps.metallic);
        if (at.has("fresnel")) {
            const At f = field_of(at, "fresnel", has_fresnel(m.type), "only glass has a Fresnel model");
            m.fresnel = f.choice({"schlick", "exact"}) == "exact" ? FresnelModel::exact : FresnelModel::schlick;
        }
        if (with_emission && at.has("emission")) m.emission = colour_or_texture(at["emission"], kMaxEmission, maps.emission);
        if (at.has("alpha")) maps.alpha.alpha = texture_lookup(at["alpha"], Usage::alpha);
        if (at.has("normal_map")) {
            maps.normal = texture_lookup(at["normal_map"], Usage::normal);
            maps.normal_strength = std::exchange(maps.normal.scale, Rgb{1}).x;
        }
        if (at.has("alpha_cutoff")) {
            if (!maps.alpha.present()) at["alpha_cutoff"].fail("applies to an \"alpha\" texture, which the material has not");
            maps.alpha.cutoff = at["alpha_cutoff"].number_in(0, 1);
        }
        return with_maps(m, maps);
    }

    // m with `maps` as its own (a new entry: another material may share m's old one).
    Material with_maps(Material m, const MaterialMaps& maps) {
        const bool any = maps.shades() || maps.alpha.present() || maps.has(maps.normal);
        if (!any) {
            m.maps = Material::kNoMaps;
        } else {
            m.maps = uint32_t(surfaces_.maps.size());
            surfaces_.maps.push_back(maps);
        }
        return m;
    }

    // m as a material of another type: that type's defaults, m's emission and cut-out.
    Material with_type(const Material& m, MaterialType type) {
        Material out = default_material(type);
        out.emission = m.emission;
        if (m.maps == Material::kNoMaps) return out;
        const MaterialMaps& old = surfaces_.maps[m.maps];
        MaterialMaps kept;
        kept.emission = old.emission;
        kept.alpha = old.alpha;
        kept.normal = old.normal;
        kept.normal_strength = old.normal_strength;
        return with_maps(out, kept);
    }

    // What a texture gives: a colour (sRGB-decoded by default), an emission (likewise), a
    // number (roughness, metallic: linear) or a cut-out's alpha (channel a by default).
    enum class Usage { colour, emission, number, alpha, normal };

    // A colour in [0, max], or a texture (its lookup in `map`, its scale returned).
    Rgb colour_or_texture(const At& at, double max, TextureLookup& map) {
        if (!at.value.is_object()) {
            map = {};
            return at.colour(max);
        }
        map = texture_lookup(at, max == 1 ? Usage::colour : Usage::emission);
        return map.scale;
    }

    double number_or_texture(const At& at, TextureLookup& map) {
        if (!at.value.is_object()) {
            map = {};
            return at.number_in(0, 1);
        }
        map = texture_lookup(at, Usage::number);
        return map.scale.x;
    }

    // {"texture": file, "scale", "uv_scale", "uv_offset", "colorspace", "channel"}.
    TextureLookup texture_lookup(const At& at, Usage usage) {
        at.expect_object({"texture", "scale", "uv_scale", "uv_offset", "colorspace", "channel"});
        if (!at.has("texture")) at.fail("a texture needs a \"texture\" file");
        TextureLookup t;
        t.texture = load_texture(at["texture"]);
        const bool colour = usage == Usage::colour || usage == Usage::emission;
        t.colorspace = colour ? ColorSpace::srgb : ColorSpace::linear;
        if (usage == Usage::alpha) t.channel = 3;
        if (at.has("colorspace"))
            t.colorspace = at["colorspace"].choice({"srgb", "linear"}) == "srgb" ? ColorSpace::srgb : ColorSpace::linear;
        if (at.has("channel")) {
            const std::string c = at["channel"].choice({"r", "g", "b", "a"});
            t.channel = int(std::string("rgba").find(c));
        }
        if (at.has("uv_scale")) uv_pair(at["uv_scale"], t.uv_scale);
        if (at.has("uv_offset")) uv_pair(at["uv_offset"], t.uv_offset);
        if (at.has("scale")) {
            const At scale = at["scale"];
            if (usage == Usage::colour) t.scale = scale.colour(1);
            else if (usage == Usage::emission) t.scale = scale.colour(kMaxEmission);
            else if (usage == Usage::normal) t.scale = Rgb{scale.number_in(0, 100)};
            else t.scale = Rgb{scale.number_in(0, 1)};
        }
        return t;
    }

    static void uv_pair(const At& at, double (&out)[2]) {
        if (!at.value.is_array() || at.value.size() != 2) at.fail("must be an array of 2 numbers");
        for (size_t i = 0; i < 2; ++i) out[i] = at.item(i).number_in(-1e6, 1e6);
    }

    // A texture file, read once however many materials use it; the scene's texels are bounded
    // per file and in all.
    const Texture* load_texture(const At& at) { return load_texture(at, scene_file(at), at.value.get<std::string>()); }

    // The texture file at `full`, which the scene names `name` at `at`.
    const Texture* load_texture(const At& at, const std::filesystem::path& full, const std::string& name) {
        if (const auto known = texture_files_.find(full); known != texture_files_.end()) return known->second.get();
        auto texture = std::static_pointer_cast<const Texture>(image_asset(at, full, name, AssetKind::texture).value);
        texture_files_.emplace(full, texture);
        surfaces_.textures.push_back(texture);
        return texture.get();
    }

    // The image file at `full` made an asset of `kind` (decoded, or found in the service's
    // cache), counted against the scene's texel limits, its negative values set to 0 with a
    // warning.
    Asset image_asset(const At& at, const std::filesystem::path& full, const std::string& name, AssetKind kind) {
        const TextureLimits per_file{limits_.max_texels_per_file};
        const auto make = [&] {
            DecodedTexture decoded = decode_texture(read_file(full.string(), limits_.max_file_bytes), name, per_file);
            return as_asset(std::move(decoded), kind);
        };
        try {
            const Asset asset = assets_ ? assets_->get(kind, full, make) : make();
            check_texture_size(name, asset.width, asset.height, per_file);
            texels_ += size_t(asset.width) * size_t(asset.height);
            if (texels_ > limits_.max_texels)
                at.fail("the scene's textures would hold more than " + std::to_string(limits_.max_texels) + " texels");
            if (asset.negative_values > 0)
                warnings_.push_back(at.path + ": " + std::to_string(asset.negative_values) + " negative values in " + name + " set to 0");
            return asset;
        } catch (const SceneError&) {
            throw;
        } catch (const std::exception& e) {
            at.fail(e.what());
        }
    }

    static Asset as_asset(DecodedTexture decoded, AssetKind kind) {
        Asset asset{nullptr, decoded.texture.width(), decoded.texture.height(), decoded.negative_values, 0};
        if (kind == AssetKind::texture) {
            auto texture = std::make_shared<const Texture>(std::move(decoded.texture));
            asset.bytes = texture->memory_bytes();
            asset.value = std::move(texture);
        } else {
            auto map = std::make_shared<const EnvironmentMap>(EnvironmentMap::from_texture(decoded.texture));
            asset.bytes = map->memory_bytes();
            asset.value = std::move(map);
        }
        return asset;
    }

    PointLight parse_point_light(const At& at, bool spot) const {
        if (spot) at.expect_object({"type", "position", "intensity", "direction", "inner_angle", "outer_angle"});
        else at.expect_object({"type", "position", "intensity"});
        if (!at.has("position")) at.fail("needs a \"position\"");
        PointLight light;
        light.position = at["position"].vec3(limits_.max_coordinate);
        if (at.has("intensity")) light.intensity = at["intensity"].colour(kMaxEmission);
        light.spot = spot;
        if (!spot) return light;
        if (at.has("direction")) light.direction = unit_direction(at["direction"], at["direction"].vec3(kMaxEmission), "must not be zero");
        const double outer = at.has("outer_angle") ? at["outer_angle"].number_in(0, 90) : 45;
        const double inner = at.has("inner_angle") ? at["inner_angle"].number_in(0, 90) : 0;
        if (!(outer > 0)) at["outer_angle"].fail("must be more than 0");
        if (!(inner < outer)) at["inner_angle"].fail("must be less than outer_angle");
        light.cos_inner = std::cos(inner * kPi / 180);
        light.cos_outer = std::cos(outer * kPi / 180);
        return light;
    }

    static SunSettings parse_sun(const At& at) {
        at.expect_object({"direction", "irradiance", "angle"});
        if (!at.has("direction")) at.fail("needs a \"direction\" toward the sun");
        SunSettings s;
        const At direction = at["direction"];
        s.direction = unit_direction(direction, direction.vec3(kMaxEmission), "must not be zero");
        if (at.has("irradiance")) s.irradiance = at["irradiance"].colour(kMaxEmission);
        if (at.has("angle")) s.angle = at["angle"].number_in(0, 179.999);
        return s;
    }

    std::shared_ptr<const Environment> parse_environment(const At& at) {
        at.expect_object({"file", "strength", "rotation", "visible"});
        if (!at.has("file")) at.fail("needs a \"file\": an equirectangular .exr or .hdr image");
        EnvironmentSettings s;
        if (at.has("strength")) s.strength = at["strength"].number_in(0, kMaxEmission);
        if (at.has("rotation")) s.rotation = at["rotation"].number_in(-3600, 3600);
        if (at.has("visible")) s.visible = at["visible"].boolean();
        const At file = at["file"];
        const Asset map = image_asset(file, scene_file(file), file.value.get<std::string>(), AssetKind::environment);
        return std::make_shared<const Environment>(std::static_pointer_cast<const EnvironmentMap>(map.value), s);
    }

    // at[key], which the material's type must have (else `message` at its path).
    static At field_of(const At& at, const char* key, bool type_has_it, const char* message) {
        const At field = at[key];
        if (!type_has_it) field.fail(message);
        return field;
    }

    static bool has_own_material(const At& object) { return object.has("material") || object.has("emission"); }

    // An object's own `material` and `emission`.
    Material object_material(const At& object) {
        Material m;
        if (object.has("material")) m = material_fields(object["material"], m, false);
        if (object.has("emission")) m.emission = object["emission"].colour(kMaxEmission);
        // Light sampling picks points over a light's whole area.
        if (m.is_emissive() && has_cutout(m)) object["material"]["alpha"].fail("an emitter cannot have cut-outs");
        return m;
    }

    bool has_cutout(const Material& m) const { return m.maps != Material::kNoMaps && surfaces_.maps[m.maps].alpha.present(); }

    uint32_t add_material(const Material& m) {
        surfaces_.materials.push_back(m);
        return uint32_t(surfaces_.materials.size() - 1);
    }

    void parse_sphere(const At& at) {
        at.expect_object({"type", "center", "radius", "material", "emission"});
        if (!at.has("center")) at.fail("a sphere needs a \"center\"");
        if (!at.has("radius")) at.fail("a sphere needs a \"radius\"");
        const Sphere s{at["center"].vec3(limits_.max_coordinate), at["radius"].positive(limits_.max_coordinate)};
        surfaces_.spheres.push_back(s);
        const Material m = object_material(at);
        if (has_cutout(m)) at["material"]["alpha"].fail("cut-outs apply to meshes only");
        sphere_materials_.push_back(add_material(m));
    }

    void parse_mesh(const At& at) {
        at.expect_object({"type", "file", "vertices", "indices", "uvs", "normals", "scale", "translate", "material",
                          "materials", "emission"});
        ObjMesh mesh;
        if (at.has("file")) {
            for (const char* key : {"vertices", "indices", "uvs", "normals"})
                if (at.has(key)) at[key].fail("a mesh file gives its own; give either file or vertices and indices");
            // The object's own material replaces the library's, which is then read only for
            // the names `materials` overrides.
            mesh = load_mesh_file(at["file"], !has_own_material(at) || at.has("materials"));
        } else {
            if (!at.has("vertices") || !at.has("indices")) at.fail("a mesh needs a \"file\", or \"vertices\" and \"indices\"");
            if (at.has("materials")) at["materials"].fail("only a mesh file's materials can be overridden by name");
            mesh = parse_inline_mesh(at);
        }
        const Vec3 scale = at.has("scale") ? parse_scale(at["scale"]) : Vec3{1};
        const Vec3 translate = at.has("translate") ? at["translate"].vec3(limits_.max_coordinate) : Vec3{};
        std::vector<Triangle>& triangles = surfaces_.triangles;
        if (triangles.size() + mesh.triangles.size() > limits_.max_triangles)
            at.fail("too many triangles in the scene (limit " + std::to_string(limits_.max_triangles) + ")");
        for (const Vec3& v : mesh.vertices)
            if (!(max_component(abs(v * scale + translate)) <= limits_.max_coordinate))
                at.fail("a vertex lies beyond the coordinate limit " + At::format(limits_.max_coordinate));
        assign_mesh_materials(at, mesh);
        add_attributes(surfaces_.attributes.uvs, mesh.uvs, mesh.triangles.size());
        add_attributes(surfaces_.attributes.normals, placed_normals(mesh, scale), mesh.triangles.size());
        const std::vector<Triangle> placed = to_triangles(mesh, scale, translate);
        triangles.insert(triangles.end(), placed.begin(), placed.end());
    }

    // A mesh's per-triangle attributes (`given`, or none) after the scene's: the scene keeps one
    // per triangle once some mesh gives them, defaults for the triangles of meshes that do not.
    template <typename T>
    void add_attributes(std::vector<T>& scene, const std::vector<T>& given, size_t count) const {
        if (given.empty() && scene.empty()) return;
        scene.resize(surfaces_.triangles.size());
        if (given.empty()) scene.resize(scene.size() + count);
        else scene.insert(scene.end(), given.begin(), given.end());
    }

    Vec3 parse_scale(const At& s) const {
        const Vec3 scale = s.value.is_number() ? Vec3{s.positive(limits_.max_coordinate)} : s.vec3(limits_.max_coordinate);
        if (!(min_component(abs(scale)) > 0)) s.fail("must not be zero");
        return scale;
    }

    // Each triangle's material: its library's (mapped by mtl_material.h), or the object's own
    // `material` for every face when given; then `materials` overrides fields by name. Faces
    // under no library material take the object's.
    void assign_mesh_materials(const At& at, const ObjMesh& mesh) {
        const Material own = object_material(at);
        const uint32_t fallback = add_material(own);
        if (mesh.triangle_material.empty()) {
            surfaces_.material_of_prim.insert(surfaces_.material_of_prim.end(), mesh.triangles.size(), fallback);
            return;
        }
        std::vector<bool> used(mesh.materials.size());
        for (const uint32_t m : mesh.triangle_material)
            if (m != kNoObjMaterial) used[m] = true;
        const bool replaced = has_own_material(at);
        const std::filesystem::path obj_folder = std::filesystem::path(at["file"].value.get<std::string>()).parent_path();
        std::vector<Material> library;
        for (size_t i = 0; i < mesh.materials.size(); ++i)
            library.push_back(replaced ? own : used[i] ? with_textures(at["file"], obj_folder, mesh.materials[i]) : mesh.materials[i].material);
        if (at.has("materials")) override_by_name(at["materials"], mesh.materials, library);
        std::vector<Material>& materials = surfaces_.materials;
        const auto first = uint32_t(materials.size());
        materials.insert(materials.end(), library.begin(), library.end());
        for (const uint32_t m : mesh.triangle_material)
            surfaces_.material_of_prim.push_back(m == kNoObjMaterial ? fallback : first + m);
        for (const std::string& w : mesh.warnings) warnings_.push_back(at["file"].path + ": " + w);
        for (size_t i = 0; i < library.size(); ++i)
            if (used[i] && !replaced) warn_ignored(at["file"], mesh.materials[i]);
    }

    // A library material with the textures it names (relative to the OBJ's folder) read.
    Material with_textures(const At& file, const std::filesystem::path& obj_folder, const ObjMaterial& m) {
        const MtlTextures& t = m.textures;
        MaterialMaps maps;
        const auto lookup = [&](const MtlTexture& texture, ColorSpace colorspace, TextureLookup& out) {
            if (texture.file.empty()) return;
            const auto full = std::filesystem::path(texture.file).has_root_path()
                                  ? std::nullopt
                                  : resolve_inside(folder_, (obj_folder / texture.file).string());
            const std::string what = "material \"" + m.name + "\": texture " + texture.file;
            if (!full) file.fail(what + ": must stay inside the scene's folder");
            out.texture = load_texture(file, *full, texture.file);
            out.colorspace = colorspace;
            for (int a = 0; a < 2; ++a) {
                out.uv_scale[a] = texture.uv_scale[a];
                out.uv_offset[a] = texture.uv_offset[a];
            }
        };
        lookup(t.albedo, ColorSpace::srgb, maps.albedo);
        lookup(t.roughness, ColorSpace::linear, maps.roughness);
        lookup(t.metallic, ColorSpace::linear, maps.metallic);
        lookup(t.emission, ColorSpace::srgb, maps.emission);
        lookup(t.alpha, ColorSpace::linear, maps.alpha.alpha);
        lookup(t.normal, ColorSpace::linear, maps.normal);
        maps.normal_strength = t.normal_strength;
        // A mask's alpha channel, or the grey of an image without one.
        if (maps.alpha.present()) maps.alpha.alpha.channel = maps.alpha.alpha.texture->channels() % 2 == 0 ? 3 : 0;
        Material out = m.material;
        if (maps.has(maps.albedo)) out.albedo = Rgb{1};
        if (maps.has(maps.emission)) out.emission = Rgb{1};
        if (maps.has(maps.roughness)) out.roughness = 1;
        if (maps.has(maps.metallic)) out.metallic = 1;
        return with_maps(out, maps);
    }

    void override_by_name(const At& at, const std::vector<ObjMaterial>& names, std::vector<Material>& library) {
        if (!at.value.is_object()) at.fail("must be an object of material names");
        for (const auto& item : at.value.items()) {
            size_t i = 0;
            while (i < names.size() && names[i].name != item.key()) ++i;
            const At field{item.value(), at.path + "." + item.key()};
            if (i == names.size()) field.fail("the OBJ's material libraries have no material of this name");
            library[i] = material_fields(field, library[i], true);
        }
    }

    void warn_ignored(const At& file, const ObjMaterial& m) {
        if (m.ignored.empty()) return;
        std::string list;
        for (const std::string& what : m.ignored) list += (list.empty() ? "" : "; ") + what;
        warnings_.push_back(file.path + ": material \"" + m.name + "\": ignored " + list);
    }

    // The file `at` names, relative to the scene's folder and inside it.
    std::filesystem::path scene_file(const At& at) const {
        if (!at.value.is_string()) at.fail("must be a file name");
        const std::filesystem::path name = at.value.get<std::string>();
        if (folder_.empty()) at.fail("file references need a scene folder");
        if (name.has_root_path()) at.fail("must be relative to the scene's folder");
        // Symlinks and ".." are resolved first: the file itself must lie inside the folder.
        const auto full = resolve_inside(folder_, name.string());
        if (!full) at.fail("must stay inside the scene's folder");
        return *full;
    }

    ObjMesh load_mesh_file(const At& at, bool with_materials) const {
        const std::filesystem::path full = scene_file(at);
        const std::filesystem::path name = at.value.get<std::string>();
        try {
            return load_obj(full.string(), limits_.max_file_bytes,
                            with_materials ? library_opener(name.parent_path()) : MtlOpener{});
        } catch (const std::exception& e) {
            at.fail(e.what());
        }
    }

    // Material libraries are named relative to their OBJ, and held to the scene's folder too.
    MtlOpener library_opener(const std::filesystem::path& obj_folder) const {
        return [this, obj_folder](const std::string& library) {
            if (std::filesystem::path(library).has_root_path())
                throw std::runtime_error("must be relative to the OBJ's folder");
            const auto full = resolve_inside(folder_, (obj_folder / library).string());
            if (!full) throw std::runtime_error("must stay inside the scene's folder");
            const std::vector<uint8_t> bytes = read_file(full->string(), limits_.max_file_bytes);
            return std::string(bytes.begin(), bytes.end());
        };
    }

    ObjMesh parse_inline_mesh(const At& at) const {
        const At vertices = at["vertices"], indices = at["indices"];
        if (!vertices.value.is_array()) vertices.fail("must be an array of [x, y, z]");
        if (!indices.value.is_array()) indices.fail("must be an array of [i, j, k]");
        if (indices.value.size() > limits_.max_triangles) indices.fail("too many triangles");
        ObjMesh mesh;
        for (size_t i = 0; i < vertices.value.size(); ++i) mesh.vertices.push_back(vertices.item(i).vec3(limits_.max_coordinate));
        const auto max_index = int64_t(mesh.vertices.size()) - 1;
        for (size_t i = 0; i < indices.value.size(); ++i) {
            const At tri = indices.item(i);
            if (!tri.value.is_array() || tri.value.size() != 3) tri.fail("must be an array of 3 vertex indices");
            if (max_index < 0) tri.fail("there are no vertices");
            mesh.triangles.push_back({uint32_t(tri.item(0).integer(0, max_index)), uint32_t(tri.item(1).integer(0, max_index)),
                                      uint32_t(tri.item(2).integer(0, max_index))});
        }
        if (at.has("uvs")) mesh.uvs = per_corner<TriangleUvs, 2>(at["uvs"], mesh, 1e6);
        if (at.has("normals")) mesh.normals = per_corner<TriangleNormals, 3>(at["normals"], mesh, 1e6);
        return mesh;
    }

    // One N-vector per vertex (UVs, normals), as each triangle's corners take them.
    template <typename T, size_t N>
    static std::vector<T> per_corner(const At& at, const ObjMesh& mesh, double max_abs) {
        if (!at.value.is_array() || at.value.size() != mesh.vertices.size())
            at.fail("must be an array of one [" + std::string(N == 2 ? "u, v" : "x, y, z") + "] per vertex (" +
                    std::to_string(mesh.vertices.size()) + ")");
        std::vector<std::array<float, N>> values;
        for (size_t i = 0; i < at.value.size(); ++i) {
            const At item = at.item(i);
            if (!item.value.is_array() || item.value.size() != N) item.fail("must be an array of " + std::to_string(N) + " numbers");
            std::array<float, N> v;
            for (size_t a = 0; a < N; ++a) v[a] = float(item.item(a).number_in(-max_abs, max_abs));
            values.push_back(v);
        }
        std::vector<T> out(mesh.triangles.size());
        for (size_t t = 0; t < mesh.triangles.size(); ++t)
            for (int k = 0; k < 3; ++k)
                for (size_t a = 0; a < N; ++a) corner_of(out[t], k)[a] = values[mesh.triangles[t][k]][a];
        return out;
    }
    static float* corner_of(TriangleUvs& t, int k) { return t.uv[k]; }
    static float* corner_of(TriangleNormals& t, int k) { return t.n[k]; }

    std::filesystem::path folder_;
    SceneLimits limits_;
    AssetCache* assets_;
    SceneSurfaces surfaces_;
    std::vector<uint32_t> sphere_materials_;
    std::vector<PointLight> point_lights_;
    std::map<std::filesystem::path, std::shared_ptr<const Texture>> texture_files_;  // by resolved path
    size_t texels_ = 0;
    std::vector<std::string> warnings_;
};

}  // namespace

LoadedScene parse_scene(const std::string& json_text, const std::filesystem::path& folder, const SceneLimits& limits,
                        AssetCache* assets) {
    json root;
    try {
        root = parse_json_text(json_text);
    } catch (const JsonTextError& e) {
        throw SceneError("", e.what(), true);
    }
    return scene_from_json(root, folder, limits, assets);
}

LoadedScene scene_from_json(const nlohmann::json& root, const std::filesystem::path& folder, const SceneLimits& limits,
                            AssetCache* assets) {
    return SceneParser(folder, limits, assets).parse(At{root, ""});
}

LoadedScene load_scene(const std::filesystem::path& file, const SceneLimits& limits, const std::filesystem::path& folder,
                       AssetCache* assets) {
    std::vector<uint8_t> bytes;
    try {
        bytes = read_file(file.string(), limits.max_file_bytes);
    } catch (const FileError& e) {
        throw SceneError("", e.what());
    }
    const auto own = file.has_parent_path() ? file.parent_path() : std::filesystem::path(".");
    return parse_scene(std::string(bytes.begin(), bytes.end()), folder.empty() ? own : folder, limits, assets);
}

Region parse_region(const nlohmann::json& value, const std::string& path, const SceneLimits& limits,
                    FieldErrors errors) {
    return region_of(At{value, path}, limits, errors);
}

void parse_adaptive(const nlohmann::json& value, const std::string& path, const SceneLimits& limits,
                    FieldErrors errors, FilmOverrides& overrides) {
    adaptive_fields(At{value, path}, limits, errors, overrides);
}

}  // namespace glint
