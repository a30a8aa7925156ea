// A job as the API shows it (README, "GET /jobs/{id}"): its state, progress and the URLs of
// its routes. The service's Job knows no URLs; they come from the route table (http/routes.h).
#pragma once

#include <string>

#include <nlohmann/json.hpp>

#include "service/job.h"

namespace glint {

// The route of job `id`, "/jobs/{id}"; its image, stream and events routes hang below it.
std::string job_url(const std::string& id);

nlohmann::json job_status(const Job& job);

}  // namespace glint
