// What PATCH /jobs/{id} accepts: a JSON object of the job's fields a client may change while it
// queues or runs; today only its priority (service/priority.h). Errors are the service's, with
// the JSON path they are about, as for a job request (http/job_request.h).
#pragma once

#include <optional>
#include <string>

namespace glint {

struct JobPatch {
    std::optional<int> priority;  // unset: unchanged
};

// {"priority": P}, P an integer in [kMinPriority, kMaxPriority]; {} changes nothing. Throws
// MalformedRequest (not JSON) or InvalidRequest (not an object, an unknown field, a bad value).
JobPatch parse_job_patch(const std::string& body);

}  // namespace glint
