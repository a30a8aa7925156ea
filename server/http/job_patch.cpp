#include "http/job_patch.h"

#include <nlohmann/json.hpp>

#include "service/errors.h"
#include "service/priority.h"

namespace glint {

JobPatch parse_job_patch(const std::string& body) {
    const nlohmann::json patch = nlohmann::json::parse(body, nullptr, false);
    if (patch.is_discarded() || !patch.is_object()) throw MalformedRequest("the body must be a JSON object");
    JobPatch out;
    for (const auto& item : patch.items()) {
        if (item.key() != "priority") throw InvalidRequest("unknown field (expected: priority)", item.key());
        const nlohmann::json& v = item.value();
        if (!v.is_number_integer() || v.get<int64_t>() < kMinPriority || v.get<int64_t>() > kMaxPriority)
            throw InvalidRequest("must be an integer in [" + std::to_string(kMinPriority) + ", " +
                                     std::to_string(kMaxPriority) + "]",
                                 "priority");
        out.priority = v.get<int>();
    }
    return out;
}

}  // namespace glint
