#include "service/farm.h"

#include "service/errors.h"

namespace glint {

nlohmann::json FarmRun::to_json() const {
    return {{"array", array}, {"merge", merge}, {"work", work.string()}, {"ranges", ranges}};
}

FarmRun FarmRun::from_json(const nlohmann::json& j) {
    try {
        return {j.at("array").get<std::string>(), j.at("merge").get<std::string>(), j.at("work").get<std::string>(),
                j.at("ranges").get<std::vector<std::string>>()};
    } catch (const nlohmann::json::exception& e) {
        throw FarmError(std::string("not a farm run: ") + e.what());
    }
}

void check_farm_settings(const RenderSettings& settings) {
    if (settings.time_limit > 0 || settings.target_error > 0)
        throw InvalidRequest("a job on the farm renders every sample it asks for: it takes no time limit or target error",
                             settings.time_limit > 0 ? "film.time_limit" : "film.target_error");
    if (settings.adaptive.on())
        throw InvalidRequest("a job on the farm renders every sample it asks for: it takes no adaptive sampling",
                             "film.adaptive");
}

}  // namespace glint
