// A job's progress as a JSON object, written in this one place for the two that show it: the
// store's state.json and the API's job status (http/job_view.h). They name two fields apart
// (README documents the status; stores on disk hold the other names), so the caller names them.
#pragma once

#include <nlohmann/json.hpp>

#include "render/renderer.h"

namespace glint {

struct ProgressNames {
    const char* seconds = "seconds";  // rendering time so far, over restarts
    const char* dropped = "dropped";  // samples dropped for a non-finite value
};

// spp_done, spp_target, seconds, samples_per_second, error_estimate (null while infinite), dropped.
nlohmann::json progress_json(const Progress& progress, const ProgressNames& names = {});
// Seconds left at the rate so far: what the API's status and the terminal's progress bar show
// as ETA; 0 before the first pass.
double eta_seconds(const Progress& progress);

// What progress_json(p) wrote, with the default names; throws nlohmann::json::exception.
Progress progress_from_json(const nlohmann::json& j);

}  // namespace glint
