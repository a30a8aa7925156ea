// A job's progress as JSON, one schema for the two that show it: the API's job status
// (http/job_view.h, documented in README) and the store's state.json.
#pragma once

#include <nlohmann/json.hpp>

#include "render/renderer.h"

namespace glint {

// spp_done, spp_target, elapsed (rendering seconds so far, over restarts), samples_per_second,
// error_estimate (null while infinite), dropped_samples (left out for a non-finite value).
nlohmann::json progress_json(const Progress& progress);
// Seconds left at the rate so far: what the API's status and the terminal's progress bar show
// as ETA; 0 before the first pass.
double eta_seconds(const Progress& progress);

// What progress_json wrote; also reads the state.json of stores written before the schema was
// shared, which named two fields `seconds` and `dropped`. Throws nlohmann::json::exception.
Progress progress_from_json(const nlohmann::json& j);

}  // namespace glint
