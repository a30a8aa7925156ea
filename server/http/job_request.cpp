#include "http/job_request.h"

#include <algorithm>
#include <optional>

#include "base/files.h"
#include "io/json_text.h"

namespace glint {
namespace {

bool is_preset_name(const std::string& name) {
    return !name.empty() && name.size() <= 64 && std::all_of(name.begin(), name.end(), [](char c) {
        return std::isalnum(static_cast<unsigned char>(c)) || c == '_' || c == '-';
    });
}

// Runs f, turning a SceneError into the service error it means.
template <typename F>
auto load_checked(F&& f) -> decltype(f()) {
    try {
        return f();
    } catch (const SceneError& e) {
        if (e.malformed()) throw MalformedRequest(e.message(), e.path());
        throw InvalidRequest(e.message(), e.path());
    }
}

constexpr FilmInteger kOverridable[] = {FilmInteger::width, FilmInteger::height, FilmInteger::spp,
                                        FilmInteger::seed};

void check_preset_fields(const nlohmann::json& request) {
    for (const auto& item : request.items()) {
        bool known = item.key() == "preset";
        for (FilmInteger field : kOverridable) known |= item.key() == film_key(field);
        if (!known)
            throw InvalidRequest(
                "unknown field (expected one of: preset, width, height, spp, seed)", item.key());
    }
}

// The request's value of `field` if it has one, an integer within the field's range.
std::optional<int64_t> film_integer(const nlohmann::json& request, FilmInteger field,
                                    const SceneLimits& limits) {
    const char* key = film_key(field);
    if (!request.contains(key)) return std::nullopt;
    const nlohmann::json& v = request.at(key);
    const IntegerRange range = film_range(field, limits);
    if (!v.is_number_integer() || !range.contains(v.get<int64_t>()))
        throw InvalidRequest("must be an integer in " + range.text(), key);
    return v.get<int64_t>();
}

FilmOverrides overrides_of(const nlohmann::json& request, const SceneLimits& limits) {
    FilmOverrides o;
    if (auto w = film_integer(request, FilmInteger::width, limits)) o.width = int(*w);
    if (auto h = film_integer(request, FilmInteger::height, limits)) o.height = int(*h);
    if (auto spp = film_integer(request, FilmInteger::spp, limits)) o.spp = uint32_t(*spp);
    if (auto seed = film_integer(request, FilmInteger::seed, limits)) o.seed = uint64_t(*seed);
    return o;
}

// {"preset": NAME, "width": W, "height": H, "spp": N, "seed": S}: every override optional.
LoadedScene parse_preset_request(const nlohmann::json& request, const std::filesystem::path& scenes,
                                 const SceneLimits& limits) {
    check_preset_fields(request);
    if (!request.at("preset").is_string()) throw InvalidRequest("must be a preset name", "preset");
    const std::filesystem::path file = preset_path(scenes, request.at("preset").get<std::string>());
    if (file.empty()) throw NotFound("no such preset (see GET /presets)", "preset");
    LoadedScene scene = load_checked([&] { return load_scene(file, limits); });
    const FilmOverrides overrides = overrides_of(request, limits);
    load_checked([&] { apply_film_overrides(overrides, scene.settings, limits); });
    return scene;
}

}  // namespace

std::filesystem::path preset_path(const std::filesystem::path& scenes, const std::string& name) {
    if (!is_preset_name(name)) return {};
    const auto file = scenes / (name + ".json");
    return std::filesystem::is_regular_file(file) ? file : std::filesystem::path{};
}

nlohmann::json parse_request_json(const std::string& body) {
    try {
        return parse_json_text(body);
    } catch (const JsonTextError& e) {
        throw MalformedRequest(e.what());
    }
}

LoadedScene parse_job_request(const std::string& body, const std::filesystem::path& scenes,
                              const SceneLimits& limits) {
    const nlohmann::json request = parse_request_json(body);
    // Both paths end with check_settings(): scene_from_json's own, or apply_film_overrides'.
    return request.is_object() && request.contains("preset")
               ? parse_preset_request(request, scenes, limits)
               : load_checked([&] { return scene_from_json(request, scenes, limits); });
}

nlohmann::json list_presets(const std::filesystem::path& scenes) {
    std::vector<std::filesystem::path> files;
    for (const auto& entry : std::filesystem::directory_iterator(scenes))
        if (entry.path().extension() == ".json" && is_preset_name(entry.path().stem().string()))
            files.push_back(entry.path());
    std::sort(files.begin(), files.end());
    nlohmann::json presets = nlohmann::json::array();
    for (const auto& file : files) {
        try {
            const std::vector<uint8_t> bytes = read_file(file.string(), size_t(16) << 20);
            const nlohmann::json scene = parse_json_text(std::string(bytes.begin(), bytes.end()));
            const nlohmann::json film = scene.value("film", nlohmann::json::object());
            presets.push_back({{"name", file.stem().string()},
                               {"description", scene.value("description", "")},
                               {"width", film.value("width", RenderSettings{}.width)},
                               {"height", film.value("height", RenderSettings{}.height)},
                               {"spp", film.value("spp", RenderSettings{}.spp)}});
        } catch (const std::exception&) {
            // A preset that does not parse is left out of the list; requesting it reports why.
        }
    }
    return presets;
}

}  // namespace glint
