#include "service/progress_json.h"

#include <cmath>

namespace glint {

using nlohmann::json;

json progress_json(const Progress& p, const ProgressNames& names) {
    return {{"spp_done", p.spp_done},
            {"spp_target", p.spp_target},
            {names.seconds, p.seconds},
            {"samples_per_second", p.samples_per_second},
            {"error_estimate", std::isfinite(p.error_estimate) ? json(p.error_estimate) : json()},
            {names.dropped, p.dropped}};
}

double eta_seconds(const Progress& p) {
    return p.spp_done > 0 ? p.seconds * (p.spp_target - p.spp_done) / p.spp_done : 0;
}

Progress progress_from_json(const json& j) {
    const ProgressNames names;
    Progress p;
    p.spp_done = j.at("spp_done").get<uint32_t>();
    p.spp_target = j.at("spp_target").get<uint32_t>();
    p.seconds = j.at(names.seconds).get<double>();
    p.samples_per_second = j.at("samples_per_second").get<double>();
    p.error_estimate =
        j.at("error_estimate").is_null() ? kInfinity : j.at("error_estimate").get<double>();
    p.dropped = j.at(names.dropped).get<uint64_t>();
    return p;
}

}  // namespace glint
