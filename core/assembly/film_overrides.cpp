#include "assembly/film_overrides.h"

#include <cmath>

namespace glint {
namespace {

[[noreturn]] void out_of(FilmInteger field, const SceneLimits& limits) {
    throw SceneError(std::string("film.") + film_key(field),
                     "must be in " + film_range(field, limits).text());
}

void check_stop_condition(const char* path, double value) {
    if (!(value >= 0) || !std::isfinite(value)) throw SceneError(path, "must be a finite number >= 0 (0: off)");
}

void check_adaptive(const AdaptiveSettings& a, const SceneLimits& limits) {
    if (!(a.threshold >= 0 && a.threshold <= kMaxAdaptiveThreshold))
        throw SceneError("film.adaptive.threshold", "must be a number in [0, 1] (0: off)");
    if (!adaptive_min_spp_range(limits).contains(a.min_spp))
        throw SceneError("film.adaptive.min_spp",
                         "must be an integer in " + adaptive_min_spp_range(limits).text() + " (0: automatic)");
}

void check_region(const RenderSettings& s) {
    if (s.whole_image()) return;
    const Region& r = s.region;
    if (!(r.x0 >= 0 && r.x0 < r.x1 && r.x1 <= s.width && r.y0 >= 0 && r.y0 < r.y1 && r.y1 <= s.height))
        throw SceneError("film.region", "[" + std::to_string(r.x0) + ", " + std::to_string(r.y0) + ", " +
                                            std::to_string(r.x1) + ", " + std::to_string(r.y1) +
                                            "] must satisfy 0 <= x0 < x1 <= width (" + std::to_string(s.width) +
                                            ") and 0 <= y0 < y1 <= height (" + std::to_string(s.height) + ")");
}

}  // namespace

std::string IntegerRange::text() const {
    // Appended piece by piece: GCC 12 warns (-Wrestrict) at "[" + std::to_string(...), wrongly.
    std::string text = "[";
    text += std::to_string(min);
    text += ", ";
    text += std::to_string(max);
    return text + "]";
}

IntegerRange film_range(FilmInteger field, const SceneLimits& limits) {
    switch (field) {
        case FilmInteger::width:
        case FilmInteger::height: return {1, limits.max_dimension};
        case FilmInteger::spp: return {1, limits.max_spp};
        case FilmInteger::seed: return {0, INT64_MAX};  // JSON integers are signed 64-bit
    }
    return {};
}

IntegerRange adaptive_min_spp_range(const SceneLimits& limits) { return {0, limits.max_spp}; }

const char* film_key(FilmInteger field) {
    static constexpr const char* kKeys[] = {"width", "height", "spp", "seed"};  // enum order
    return kKeys[size_t(field)];
}

Encoding encoding_named(const std::string& name) {
    return name == "srgb" ? Encoding::srgb : Encoding::gamma22;
}

void apply_film_overrides(const FilmOverrides& o, RenderSettings& s, const SceneLimits& limits) {
    if (o.first_sample) s.adaptive.job_spp = o.job_spp.value_or(s.spp);  // before spp becomes the part's
    if (o.spp) s.spp = *o.spp;
    if (o.width) s.width = *o.width;
    if (o.height) s.height = *o.height;
    if (o.seed) s.seed = *o.seed;
    if (o.encoding) s.encoding = *o.encoding;
    if (o.first_sample) s.first_sample = *o.first_sample;
    if (o.target_error) s.target_error = *o.target_error;
    if (o.time_limit) s.time_limit = *o.time_limit;
    if (o.region) s.region = *o.region;
    if (o.aovs) s.aovs = *o.aovs;
    if (o.adaptive_threshold) s.adaptive.threshold = *o.adaptive_threshold;
    if (o.adaptive_min_spp) s.adaptive.min_spp = *o.adaptive_min_spp;
    check_settings(s, limits);
}

void check_settings(const RenderSettings& s, const SceneLimits& limits) {
    if (!film_range(FilmInteger::width, limits).contains(s.width))
        out_of(FilmInteger::width, limits);
    if (!film_range(FilmInteger::height, limits).contains(s.height))
        out_of(FilmInteger::height, limits);
    if (int64_t(s.width) * s.height > limits.max_pixels)
        throw SceneError("film", "image of " + std::to_string(int64_t(s.width) * s.height) +
                                     " pixels exceeds the limit of " +
                                     std::to_string(limits.max_pixels));
    if (!film_range(FilmInteger::spp, limits).contains(s.spp)) out_of(FilmInteger::spp, limits);
    if (s.first_sample % samples_per_round(s.filter) != 0)
        throw SceneError("--samples", "must start at a multiple of " +
                                          std::to_string(samples_per_round(s.filter)) +
                                          " (the tent filter renders whole rounds of 4 subpixels)");
    check_stop_condition("film.target_error", s.target_error);
    check_stop_condition("film.time_limit", s.time_limit);
    check_adaptive(s.adaptive, limits);
    check_region(s);
}

}  // namespace glint
