// What POST /render and POST /jobs accept: a full scene, or {"preset": NAME} with overrides of
// width, height, spp and seed. Errors carry the HTTP status and the JSON path they are about.
#pragma once

#include <filesystem>
#include <stdexcept>
#include <string>

#include <nlohmann/json.hpp>

#include "job_manager.h"

namespace glint {

struct RequestError : std::runtime_error {
    RequestError(int status_, const std::string& message, const std::string& path_ = "")
        : std::runtime_error(message), status(status_), path(path_) {}
    int status;        // 400 malformed, 404 unknown preset, 422 invalid or over a limit
    std::string path;  // JSON path of the offending field, if any
};

LoadedScene parse_job_request(const std::string& body, const std::filesystem::path& scenes, const ServiceLimits& limits);

// The scenes folder's *.json files, by name (file stem), with their descriptions and film sizes.
nlohmann::json list_presets(const std::filesystem::path& scenes);
// A preset's path, or an empty path when the name is not a preset (names are [A-Za-z0-9_-]+).
std::filesystem::path preset_path(const std::filesystem::path& scenes, const std::string& name);

}  // namespace glint
