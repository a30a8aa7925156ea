// What PATCH /jobs/{id} accepts: {"priority": n}, the one thing of a job that may change once it
// is submitted. Errors are the service's (service/errors.h), with the JSON path they are about.
#pragma once

#include <optional>
#include <string>

namespace glint {

struct JobPatch {
    std::optional<int> priority;
};

// Throws MalformedRequest (not a JSON object) or InvalidRequest (an unknown field, a bad value).
JobPatch parse_job_patch(const std::string& body);

}  // namespace glint
