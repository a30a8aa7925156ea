#include "http/job_patch.h"

#include <nlohmann/json.hpp>

#include "http/job_request.h"
#include "service/errors.h"

namespace glint {
JobPatch parse_job_patch(const std::string& body) {
    const nlohmann::json patch = parse_request_json(body);
    if (!patch.is_object()) throw InvalidRequest("must be an object");
    JobPatch result;
    for (const auto& [key, value] : patch.items()) {
        if (key != "priority") throw InvalidRequest("unknown field (expected: priority)", key);
        result.priority = priority_in(value);
    }
    return result;
}

}  // namespace glint
