#include "http/job_patch.h"

#include <nlohmann/json.hpp>

#include "http/job_request.h"
#include "service/errors.h"
#include "service/priority.h"

namespace glint {
namespace {

// An integer priority; 2.0 is not one, as no integer of a job request is. nlohmann keeps a
// number >= 0 unsigned, and 18446744073709551615 read as int64_t would be -1: compare it as it is.
bool is_priority(const nlohmann::json& v) {
    if (v.is_number_unsigned()) return v.get<uint64_t>() <= uint64_t(kMaxPriority);
    return v.is_number_integer() && v.get<int64_t>() >= kMinPriority && v.get<int64_t>() <= kMaxPriority;
}

}  // namespace

JobPatch parse_job_patch(const std::string& body) {
    const nlohmann::json patch = parse_request_json(body);
    if (!patch.is_object()) throw InvalidRequest("must be an object");
    JobPatch result;
    for (const auto& [key, value] : patch.items()) {
        if (key != "priority") throw InvalidRequest("unknown field (expected: priority)", key);
        if (!is_priority(value))
            throw InvalidRequest("must be an integer in [" + std::to_string(kMinPriority) + ", " +
                                     std::to_string(kMaxPriority) + "]",
                                 "priority");
        result.priority = value.get<int>();
    }
    return result;
}

}  // namespace glint
