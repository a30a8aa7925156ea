// Scene files: JSON in which every field has a default, unknown fields are errors and every
// error names the JSON path it is about (`objects[3].radius: must be > 0`).
#pragma once

#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include <nlohmann/json_fwd.hpp>

#include "assembly/asset_cache.h"
#include "assembly/film_overrides.h"
#include "assembly/scene_limits.h"
#include "render/settings.h"
#include "scene/scene.h"

namespace glint {

struct LoadedScene {
    std::shared_ptr<const Scene> scene;
    RenderSettings settings;  // the file's film settings, to be overridden per job
    // What the scene asks for that glint does not model (an OBJ material's texture, ...), each
    // line led by the JSON path it is about. The scene renders without it.
    std::vector<std::string> warnings;
};

// `folder` is where mesh files are looked up; file references outside it are refused, and
// with an empty folder every file reference is refused. Text that is not JSON (io/json_text.h)
// is a SceneError with malformed() set. With `assets`, texture and environment files are taken
// from that cache, and what is decoded is kept there.
LoadedScene parse_scene(const std::string& json_text, const std::filesystem::path& folder,
                        const SceneLimits& limits = {}, AssetCache* assets = nullptr);
// The same, from JSON parsed already (a request body, parsed to see whether it names a preset).
LoadedScene scene_from_json(const nlohmann::json& root, const std::filesystem::path& folder,
                            const SceneLimits& limits = {}, AssetCache* assets = nullptr);
// Mesh files are looked up in `folder`, or the scene file's own folder when it is empty.
LoadedScene load_scene(const std::filesystem::path& file, const SceneLimits& limits = {},
                       const std::filesystem::path& folder = {}, AssetCache* assets = nullptr);

// How the errors of film.region and film.adaptive read. A scene file's say what is wrong where
// ("film.region[2]: must be in [0, 16384]"); a preset request's say everything the field must
// be, at the field ("region: must be an array [x0, y0, x1, y1] of 4 integers in [0, 16384]"),
// for a client that reads the message without the scene format at hand.
enum class FieldErrors { at_fault, whole_field };

// film.region, [x0, y0, x1, y1], from `value` at JSON path `path`; throws SceneError. The one
// parser of it, for a scene's film and a preset request alike.
Region parse_region(const nlohmann::json& value, const std::string& path, const SceneLimits& limits,
                    FieldErrors errors);
// The fields of film.adaptive, {"threshold": T, "min_spp": N}, that `value` gives, into
// `overrides`; throws SceneError. check_settings() bounds the threshold.
void parse_adaptive(const nlohmann::json& value, const std::string& path, const SceneLimits& limits,
                    FieldErrors errors, FilmOverrides& overrides);

}  // namespace glint
