// What POST /render and POST /jobs accept: a full scene, or {"preset": NAME} with overrides of
// width, height, spp, seed, time_limit, target_error, region and aovs; either may give the job a
// priority (top level). Errors are the service's (service/errors.h), with the JSON path they
// are about; http/error_response.h gives each its status.
#pragma once

#include <filesystem>
#include <string>

#include <nlohmann/json.hpp>

#include "assembly/scene_loader.h"
#include "service/errors.h"
#include "service/job_spec.h"

namespace glint {

// A request body as JSON (io/json_text.h); MalformedRequest, naming the byte at fault, if it
// is not.
nlohmann::json parse_request_json(const std::string& body);

// A job's priority from its JSON value; InvalidRequest (path "priority") unless an integer in
// [kMinPriority, kMaxPriority].
int priority_in(const nlohmann::json& value);

// The job a request body describes; throws MalformedRequest, InvalidRequest or NotFound (an
// unknown preset).
JobSpec parse_job_request(const std::string& body, const std::filesystem::path& scenes, const SceneLimits& limits,
                             AssetCache* assets = nullptr);

// The scenes folder's *.json files, by name (file stem), with their descriptions and film sizes.
nlohmann::json list_presets(const std::filesystem::path& scenes);
// A preset's path, or an empty path when the name is not a preset (names are [A-Za-z0-9_-]+).
std::filesystem::path preset_path(const std::filesystem::path& scenes, const std::string& name);

}  // namespace glint
