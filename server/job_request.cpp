#include "job_request.h"

#include <algorithm>

#include "base/files.h"

namespace glint {
namespace {

bool is_preset_name(const std::string& name) {
    return !name.empty() && name.size() <= 64 && std::all_of(name.begin(), name.end(), [](char c) {
        return std::isalnum(static_cast<unsigned char>(c)) || c == '_' || c == '-';
    });
}

// Runs f, turning a SceneError into the request error it means over HTTP.
template <typename F>
auto load_checked(F&& f) -> decltype(f()) {
    try {
        return f();
    } catch (const SceneError& e) {
        throw RequestError(e.malformed() ? 400 : 422, e.message(), e.path());
    }
}

// {"preset": NAME, "width": W, "height": H, "spp": N, "seed": S}: every override optional.
LoadedScene parse_preset_request(const nlohmann::json& request, const std::filesystem::path& scenes,
                                 const ServiceLimits& limits) {
    for (const auto& item : request.items())
        if (item.key() != "preset" && item.key() != "width" && item.key() != "height" && item.key() != "spp" &&
            item.key() != "seed")
            throw RequestError(422, "unknown field (expected one of: preset, width, height, spp, seed)", item.key());
    if (!request["preset"].is_string()) throw RequestError(422, "must be a preset name", "preset");
    const std::filesystem::path file = preset_path(scenes, request["preset"].get<std::string>());
    if (file.empty()) throw RequestError(404, "no such preset (see GET /presets)", "preset");
    LoadedScene scene = load_checked([&] { return load_scene(file, limits.scene); });
    auto integer = [&](const char* key, int64_t max) -> std::optional<int64_t> {
        if (!request.contains(key)) return std::nullopt;
        const auto& v = request[key];
        if (!v.is_number_integer() || v.get<int64_t>() < (std::string(key) == "seed" ? 0 : 1) || v.get<int64_t>() > max)
            throw RequestError(422, "must be an integer in [" + std::string(std::string(key) == "seed" ? "0" : "1") +
                                        ", " + std::to_string(max) + "]",
                               key);
        return v.get<int64_t>();
    };
    if (auto w = integer("width", limits.scene.max_dimension)) scene.settings.width = int(*w);
    if (auto h = integer("height", limits.scene.max_dimension)) scene.settings.height = int(*h);
    if (auto spp = integer("spp", limits.scene.max_spp)) scene.settings.spp = uint32_t(*spp);
    if (auto seed = integer("seed", INT64_MAX)) scene.settings.seed = uint64_t(*seed);
    return scene;
}

}  // namespace

std::filesystem::path preset_path(const std::filesystem::path& scenes, const std::string& name) {
    if (!is_preset_name(name)) return {};
    const auto file = scenes / (name + ".json");
    return std::filesystem::is_regular_file(file) ? file : std::filesystem::path{};
}

LoadedScene parse_job_request(const std::string& body, const std::filesystem::path& scenes, const ServiceLimits& limits) {
    nlohmann::json request;
    try {
        // Bounded like the scene parser: 16 MiB of '[' would otherwise build 16 M nested arrays.
        request = nlohmann::json::parse(body, [](int depth, nlohmann::json::parse_event_t, nlohmann::json&) {
            if (depth > kMaxJsonDepth)
                throw RequestError(400, "JSON nested deeper than " + std::to_string(kMaxJsonDepth) + " levels");
            return true;
        });
    } catch (const nlohmann::json::exception&) {  // syntax, or a number out of range (1e999)
        load_checked([&] { return parse_scene(body, scenes, limits.scene); });  // the scene parser's message
    }
    LoadedScene scene = request.is_object() && request.contains("preset")
                            ? parse_preset_request(request, scenes, limits)
                            : load_checked([&] { return parse_scene(body, scenes, limits.scene); });
    load_checked([&] { check_settings(scene.settings, limits.scene); });
    return scene;
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
            const nlohmann::json scene = nlohmann::json::parse(read_file(file.string(), size_t(16) << 20));
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
