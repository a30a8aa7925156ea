#include "io/scene_loader.h"

#include <nlohmann/json.hpp>

#include <initializer_list>

#include "base/files.h"
#include "io/json_text.h"
#include "io/obj_loader.h"

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

class SceneParser {
public:
    SceneParser(const std::filesystem::path& folder, const SceneLimits& limits) : folder_(folder), limits_(limits) {}

    LoadedScene parse(const At& root) {
        root.expect_object({"description", "camera", "film", "integrator", "objects"});
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
        loaded.scene = std::make_shared<const Scene>(camera, background, integrator, std::move(spheres_),
                                                     std::move(triangles_), std::move(materials_),
                                                     std::move(material_of_prim_));
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
        if (at.has("region")) s.region = region(at["region"]);
        if (at.has("aovs")) s.aovs = at["aovs"].boolean();
        if (at.has("adaptive")) s.adaptive = adaptive(at["adaptive"]);
        return s;
    }

    // {"threshold": T, "min_spp": N}; check_settings() bounds the threshold.
    AdaptiveSettings adaptive(const At& at) const {
        at.expect_object({"threshold", "min_spp"});
        AdaptiveSettings a;
        if (at.has("threshold")) a.threshold = at["threshold"].number();
        const IntegerRange range = adaptive_min_spp_range(limits_);
        if (at.has("min_spp")) a.min_spp = uint32_t(at["min_spp"].integer(range.min, range.max));
        return a;
    }

    // [x0, y0, x1, y1]: pixels, rows from the top; check_region() checks it against the size.
    Region region(const At& at) const {
        if (!at.value.is_array() || at.value.size() != 4) at.fail("must be an array [x0, y0, x1, y1] of 4 integers");
        int v[4];
        for (size_t i = 0; i < 4; ++i) v[i] = int(at.item(i).integer(0, limits_.max_dimension));
        return {v[0], v[1], v[2], v[3]};
    }

    int64_t film_integer(const At& film, FilmInteger field) const {
        const IntegerRange range = film_range(field, limits_);
        return film[film_key(field)].integer(range.min, range.max);
    }

    static IntegratorSettings parse_integrator(const At& at) {
        at.expect_object({"light_sampling", "light_tracing", "max_depth", "rr_depth", "accelerator", "direct_view_rays"});
        IntegratorSettings s;
        if (at.has("light_sampling")) s.light_sampling = at["light_sampling"].boolean();
        if (at.has("max_depth")) s.max_depth = int(at["max_depth"].integer(1, 100000));
        if (at.has("rr_depth")) s.rr_depth = int(at["rr_depth"].integer(0, 100000));
        if (at.has("direct_view_rays")) s.direct_view_rays = int(at["direct_view_rays"].integer(0, 64));
        if (at.has("accelerator")) {
            const std::string a = at["accelerator"].choice({"auto", "bvh", "list"});
            s.accelerator = a == "auto" ? Accelerator::automatic : a == "bvh" ? Accelerator::bvh : Accelerator::list;
        }
        if (at.has("light_tracing")) {
            const std::string t = at["light_tracing"].choice({"auto", "on", "off"});
            s.light_tracing = t == "auto" ? LightTracing::automatic : t == "on" ? LightTracing::on : LightTracing::off;
        }
        return s;
    }

    void parse_objects(const At& at) {
        if (!at.value.is_array()) at.fail("must be an array");
        if (at.value.size() > limits_.max_objects)
            at.fail("too many objects (limit " + std::to_string(limits_.max_objects) + ")");
        for (size_t i = 0; i < at.value.size(); ++i) {
            const At object = at.item(i);
            if (!object.value.is_object()) object.fail("must be an object");
            if (!object.has("type")) object.fail("needs a \"type\": \"sphere\" or \"mesh\"");
            if (object["type"].choice({"sphere", "mesh"}) == "sphere") parse_sphere(object);
            else parse_mesh(object);
        }
        // Spheres come first in the primitive numbering (see Geometry).
        material_of_prim_.insert(material_of_prim_.begin(), sphere_materials_.begin(), sphere_materials_.end());
    }

    static MaterialType material_type(const At& at) {
        return material_type_named(at.choice({"diffuse", "mirror", "glass", "metal", "plastic"}).c_str());
    }

    // The fields `at` gives, over `m`. A new type brings its own defaults (material.h) for the
    // fields not given with it; each field must be one the type has.
    static Material material_fields(const At& at, Material m, bool with_emission) {
        if (with_emission) at.expect_object({"type", "albedo", "ior", "roughness", "metallic", "fresnel", "emission"});
        else at.expect_object({"type", "albedo", "ior", "roughness", "metallic", "fresnel"});
        if (at.has("type")) {
            const MaterialType type = material_type(at["type"]);
            if (type != m.type) m = with_type(m, type);
        }
        // Albedo above 1 would create energy.
        if (at.has("albedo")) m.albedo = at["albedo"].colour(1);
        if (at.has("ior")) m.ior = field_of(at, "ior", has_ior(m.type), "only glass and plastic have an index of refraction").number_in(1e-3, 1e3);
        if (at.has("roughness"))
            m.roughness = field_of(at, "roughness", has_roughness(m.type), "a diffuse material has no roughness").number_in(0, 1);
        if (at.has("metallic"))
            m.metallic = field_of(at, "metallic", has_metallic(m.type), "only metal and plastic have a metallic mix").number_in(0, 1);
        if (at.has("fresnel")) {
            const At f = field_of(at, "fresnel", has_fresnel(m.type), "only glass has a Fresnel model");
            m.fresnel = f.choice({"schlick", "exact"}) == "exact" ? FresnelModel::exact : FresnelModel::schlick;
        }
        if (with_emission && at.has("emission")) m.emission = at["emission"].colour(kMaxEmission);
        return m;
    }

    // m as a material of another type: that type's defaults, m's emission.
    static Material with_type(const Material& m, MaterialType type) {
        Material out = default_material(type);
        out.emission = m.emission;
        return out;
    }

    // at[key], which the material's type must have (else `message` at its path).
    static At field_of(const At& at, const char* key, bool type_has_it, const char* message) {
        const At field = at[key];
        if (!type_has_it) field.fail(message);
        return field;
    }

    static bool has_own_material(const At& object) { return object.has("material") || object.has("emission"); }

    // An object's own `material` and `emission`.
    static Material object_material(const At& object) {
        Material m;
        if (object.has("material")) m = material_fields(object["material"], m, false);
        if (object.has("emission")) m.emission = object["emission"].colour(kMaxEmission);
        return m;
    }

    uint32_t add_material(const Material& m) {
        materials_.push_back(m);
        return uint32_t(materials_.size() - 1);
    }

    void parse_sphere(const At& at) {
        at.expect_object({"type", "center", "radius", "material", "emission"});
        if (!at.has("center")) at.fail("a sphere needs a \"center\"");
        if (!at.has("radius")) at.fail("a sphere needs a \"radius\"");
        const Sphere s{at["center"].vec3(limits_.max_coordinate), at["radius"].positive(limits_.max_coordinate)};
        spheres_.push_back(s);
        sphere_materials_.push_back(add_material(object_material(at)));
    }

    void parse_mesh(const At& at) {
        at.expect_object({"type", "file", "vertices", "indices", "scale", "translate", "material", "materials", "emission"});
        ObjMesh mesh;
        if (at.has("file")) {
            if (at.has("vertices") || at.has("indices")) at.fail("give either file or vertices and indices, not both");
            // The object's own material replaces the library's, which is then read only for
            // the names `materials` overrides.
            mesh = load_mesh_file(at["file"], !has_own_material(at) || at.has("materials"));
        } else {
            if (!at.has("vertices") || !at.has("indices")) at.fail("a mesh needs a \"file\", or \"vertices\" and \"indices\"");
            if (at.has("materials")) at["materials"].fail("only a mesh file's materials can be overridden by name");
            mesh = parse_inline_mesh(at["vertices"], at["indices"]);
        }
        const Vec3 scale = at.has("scale") ? parse_scale(at["scale"]) : Vec3{1};
        const Vec3 translate = at.has("translate") ? at["translate"].vec3(limits_.max_coordinate) : Vec3{};
        if (triangles_.size() + mesh.triangles.size() > limits_.max_triangles)
            at.fail("too many triangles in the scene (limit " + std::to_string(limits_.max_triangles) + ")");
        for (const Vec3& v : mesh.vertices)
            if (!(max_component(abs(v * scale + translate)) <= limits_.max_coordinate))
                at.fail("a vertex lies beyond the coordinate limit " + At::format(limits_.max_coordinate));
        assign_mesh_materials(at, mesh);
        const std::vector<Triangle> placed = to_triangles(mesh, scale, translate);
        triangles_.insert(triangles_.end(), placed.begin(), placed.end());
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
            material_of_prim_.insert(material_of_prim_.end(), mesh.triangles.size(), fallback);
            return;
        }
        const bool replaced = has_own_material(at);
        std::vector<Material> library;
        for (const ObjMaterial& m : mesh.materials) library.push_back(replaced ? own : m.material);
        if (at.has("materials")) override_by_name(at["materials"], mesh.materials, library);
        const auto first = uint32_t(materials_.size());
        materials_.insert(materials_.end(), library.begin(), library.end());
        std::vector<bool> used(library.size());
        for (const uint32_t m : mesh.triangle_material) {
            material_of_prim_.push_back(m == kNoObjMaterial ? fallback : first + m);
            if (m != kNoObjMaterial) used[m] = true;
        }
        for (const std::string& w : mesh.warnings) warnings_.push_back(at["file"].path + ": " + w);
        for (size_t i = 0; i < library.size(); ++i)
            if (used[i] && !replaced) warn_ignored(at["file"], mesh.materials[i]);
    }

    void override_by_name(const At& at, const std::vector<ObjMaterial>& names, std::vector<Material>& library) const {
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

    ObjMesh load_mesh_file(const At& at, bool with_materials) const {
        if (!at.value.is_string()) at.fail("must be a file name");
        const std::filesystem::path name = at.value.get<std::string>();
        if (folder_.empty()) at.fail("file references need a scene folder");
        if (name.has_root_path()) at.fail("must be relative to the scene's folder");
        // Symlinks and ".." are resolved first: the file itself must lie inside the folder.
        const auto full = resolve_inside(folder_, name.string());
        if (!full) at.fail("must stay inside the scene's folder");
        try {
            return load_obj(full->string(), limits_.max_file_bytes,
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

    ObjMesh parse_inline_mesh(const At& vertices, const At& indices) const {
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
        return mesh;
    }

    std::filesystem::path folder_;
    SceneLimits limits_;
    std::vector<Sphere> spheres_;
    std::vector<Triangle> triangles_;
    std::vector<Material> materials_;
    std::vector<uint32_t> sphere_materials_, material_of_prim_;
    std::vector<std::string> warnings_;
};

}  // namespace

LoadedScene parse_scene(const std::string& json_text, const std::filesystem::path& folder, const SceneLimits& limits) {
    json root;
    try {
        root = parse_json_text(json_text);
    } catch (const JsonTextError& e) {
        throw SceneError("", e.what(), true);
    }
    return scene_from_json(root, folder, limits);
}

LoadedScene scene_from_json(const nlohmann::json& root, const std::filesystem::path& folder, const SceneLimits& limits) {
    return SceneParser(folder, limits).parse(At{root, ""});
}

LoadedScene load_scene(const std::filesystem::path& file, const SceneLimits& limits, const std::filesystem::path& folder) {
    std::vector<uint8_t> bytes;
    try {
        bytes = read_file(file.string(), limits.max_file_bytes);
    } catch (const FileError& e) {
        throw SceneError("", e.what());
    }
    const auto own = file.has_parent_path() ? file.parent_path() : std::filesystem::path(".");
    return parse_scene(std::string(bytes.begin(), bytes.end()), folder.empty() ? own : folder, limits);
}

}  // namespace glint
