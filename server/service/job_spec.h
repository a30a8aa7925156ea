// A job as the service takes it, in the service's own terms: the HTTP layer makes one from a
// request body (http/job_request.h), and the store's copy of that body is made into one again
// when a restarted server takes its jobs back.
#pragma once

#include <string>

#include <nlohmann/json.hpp>

#include "assembly/scene_loader.h"

namespace glint {

// Where a farm's parts read the job's scene: a preset of the scenes folder by name, or else the
// scene as the request gave it (without the job's own fields, such as its priority), whose mesh
// files are in the scenes folder. Either way the job's settings say what to render of it.
struct SceneSource {
    std::string preset;
    nlohmann::json scene;
};

struct JobSpec {
    LoadedScene scene;
    int priority = 0;  // in [kMinPriority, kMaxPriority] (service/priority.h)
    SceneSource source;
};

}  // namespace glint
