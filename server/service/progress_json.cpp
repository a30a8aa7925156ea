#include "service/progress_json.h"

#include <cmath>

namespace glint {

using nlohmann::json;

json progress_json(const Progress& p) {
    return {{"spp_done", p.spp_done},
            {"spp_target", p.spp_target},
            {"mean_spp", p.mean_spp},
            {"pixels", p.pixels},
            {"active_pixels", p.active_pixels},
            {"elapsed", p.seconds},
            {"samples_per_second", p.samples_per_second},
            {"error_estimate", std::isfinite(p.error_estimate) ? json(p.error_estimate) : json()},
            {"dropped_samples", p.dropped}};
}

double eta_seconds(const Progress& p) {
    return p.spp_done > 0 ? p.seconds * (p.spp_target - p.spp_done) / p.spp_done : 0;
}

namespace {

// The field `name`, or `old_name` in a store written before the schema was shared.
const json& field(const json& j, const char* name, const char* old_name) {
    return j.contains(name) ? j.at(name) : j.at(old_name);
}

}  // namespace

Progress progress_from_json(const json& j) {
    Progress p;
    p.spp_done = j.at("spp_done").get<uint32_t>();
    p.spp_target = j.at("spp_target").get<uint32_t>();
    p.seconds = field(j, "elapsed", "seconds").get<double>();
    p.samples_per_second = j.at("samples_per_second").get<double>();
    p.error_estimate =
        j.at("error_estimate").is_null() ? kInfinity : j.at("error_estimate").get<double>();
    p.dropped = field(j, "dropped_samples", "dropped").get<uint64_t>();
    // Absent from stores written before adaptive sampling: every pixel had spp_done.
    p.mean_spp = j.value("mean_spp", double(p.spp_done));
    p.pixels = j.value("pixels", uint64_t(0));
    p.active_pixels = j.value("active_pixels", p.pixels);
    return p;
}

}  // namespace glint
