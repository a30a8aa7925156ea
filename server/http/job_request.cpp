#include "http/job_request.h"

#include <algorithm>
#include <optional>

#include "base/files.h"
#include "io/json_text.h"
#include "service/priority.h"

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

constexpr const char* kPresetFields[] = {"preset",     "width",        "height",   "spp",    "seed",
                                         "time_limit", "target_error", "priority", "region", "aovs",
                                         "adaptive"};

void check_preset_fields(const nlohmann::json& request) {
    for (const auto& item : request.items()) {
        if (std::find_if(std::begin(kPresetFields), std::end(kPresetFields),
                         [&](const char* key) { return item.key() == key; }) != std::end(kPresetFields))
            continue;
        std::string list;
        for (const char* key : kPresetFields) list += std::string(list.empty() ? "" : ", ") + key;
        throw InvalidRequest("unknown field (expected one of: " + list + ")", item.key());
    }
}

// The request's value of `key` if it has one: a number (check_settings() bounds it).
std::optional<double> number(const nlohmann::json& request, const char* key) {
    if (!request.contains(key)) return std::nullopt;
    const nlohmann::json& v = request.at(key);
    if (!v.is_number()) throw InvalidRequest("must be a number", key);
    return v.get<double>();
}

// The request's value of `key` if it has one: true or false.
std::optional<bool> boolean(const nlohmann::json& request, const char* key) {
    if (!request.contains(key)) return std::nullopt;
    const nlohmann::json& v = request.at(key);
    if (!v.is_boolean()) throw InvalidRequest("must be true or false", key);
    return v.get<bool>();
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
    o.time_limit = number(request, "time_limit");
    o.target_error = number(request, "target_error");
    // Read as a scene's film.region and film.adaptive are, with errors naming the whole field.
    if (request.contains("region"))
        o.region = load_checked([&] { return parse_region(request.at("region"), "region", limits, FieldErrors::whole_field); });
    o.aovs = boolean(request, "aovs");
    if (request.contains("adaptive"))
        load_checked([&] { parse_adaptive(request.at("adaptive"), "adaptive", limits, FieldErrors::whole_field, o); });
    return o;
}

// {"preset": NAME, "width": W, ...}: every override optional.
LoadedScene parse_preset_request(const nlohmann::json& request, const std::filesystem::path& scenes,
                                 const SceneLimits& limits, AssetCache* assets) {
    check_preset_fields(request);
    if (!request.at("preset").is_string()) throw InvalidRequest("must be a preset name", "preset");
    const std::filesystem::path file = preset_path(scenes, request.at("preset").get<std::string>());
    if (file.empty()) throw NotFound("no such preset (see GET /presets)", "preset");
    LoadedScene scene = load_checked([&] { return load_scene(file, limits, {}, assets); });
    const FilmOverrides overrides = overrides_of(request, limits);
    try {
        apply_film_overrides(overrides, scene.settings, limits);
    } catch (const SceneError& e) {
        // The same check as a scene file's film; here the fields are the request's own.
        const std::string path = e.path().starts_with("film.") ? e.path().substr(5) : e.path();
        throw InvalidRequest(e.message(), path);
    }
    return scene;
}

// The top-level "priority" of any job body, which is the job's and not the scene's.
int priority_of(const nlohmann::json& request) {
    return request.is_object() && request.contains("priority") ? priority_in(request.at("priority")) : 0;
}

}  // namespace

// An integer; 2.0 is not one, as no integer of a job request is. nlohmann keeps a number >= 0
// unsigned, and 18446744073709551615 read as int64_t would be -1: it is compared as it is.
int priority_in(const nlohmann::json& v) {
    const bool in_range = v.is_number_unsigned() ? v.get<uint64_t>() <= uint64_t(kMaxPriority)
                                                 : v.is_number_integer() && v.get<int64_t>() >= kMinPriority &&
                                                       v.get<int64_t>() <= kMaxPriority;
    if (!in_range)
        throw InvalidRequest("must be an integer in [" + std::to_string(kMinPriority) + ", " +
                                 std::to_string(kMaxPriority) + "]",
                             "priority");
    return v.get<int>();
}

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

JobSpec parse_job_request(const std::string& body, const std::filesystem::path& scenes, const SceneLimits& limits,
                          AssetCache* assets) {
    nlohmann::json request = parse_request_json(body);
    // Both paths end with check_settings(): scene_from_json's own, or apply_film_overrides'.
    const int priority = priority_of(request);
    if (request.is_object() && request.contains("preset"))
        return {parse_preset_request(request, scenes, limits, assets), priority,
                {request.at("preset").get<std::string>(), {}}};
    if (request.is_object()) request.erase("priority");  // the job's, not the scene's
    LoadedScene scene = load_checked([&] { return scene_from_json(request, scenes, limits, assets); });
    return {std::move(scene), priority, {"", std::move(request)}};
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
