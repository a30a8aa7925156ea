// The film settings a command line (`glint render --spp`) or a job request ({"preset", "spp"})
// may set on top of a scene file's, and the one check of a film's settings. The scene loader,
// the command line and the HTTP request parser all take the bounds of width, height, spp and
// seed from here and end with check_settings(), so the three cannot drift apart.
#pragma once

#include <cstdint>
#include <optional>
#include <string>

#include "assembly/scene_limits.h"
#include "render/settings.h"

namespace glint {

// The film's integer fields that a scene file, a command line or a request may set.
enum class FilmInteger { width, height, spp, seed };

struct IntegerRange {
    int64_t min = 0, max = 0;
    bool contains(int64_t v) const { return v >= min && v <= max; }
    std::string text() const;  // "[1, 4096]", as error messages quote it
};

// The values `field` may take under `limits`.
IntegerRange film_range(FilmInteger field, const SceneLimits& limits);
// The name of `field` in a scene's "film" object and in a preset request.
const char* film_key(FilmInteger field);

// film.adaptive: the threshold's range ([0, 1], 0: off) and min_spp's ([0, max_spp], 0: automatic).
constexpr double kMaxAdaptiveThreshold = 1;
IntegerRange adaptive_min_spp_range(const SceneLimits& limits);

// "srgb" or "gamma2.2", the names film.encoding and --encoding accept (checked by their parsers).
Encoding encoding_named(const std::string& name);

// Each set field replaces the scene's; unset ones keep it.
struct FilmOverrides {
    std::optional<int> width, height;
    std::optional<uint32_t> spp;
    std::optional<uint64_t> seed;
    std::optional<Encoding> encoding;
    std::optional<uint32_t> first_sample;
    std::optional<double> target_error, time_limit;
    std::optional<Region> region;
    std::optional<bool> aovs;
    std::optional<double> adaptive_threshold;
    std::optional<uint32_t> adaptive_min_spp;
    // With first_sample (a part of a job): the whole job's spp; unset, the scene's film.spp.
    std::optional<uint32_t> job_spp;
};

// Applies the overrides to `settings`, then checks the result with check_settings().
void apply_film_overrides(const FilmOverrides& overrides, RenderSettings& settings,
                          const SceneLimits& limits);

// Checks settings after the scene file and any overrides; throws SceneError naming the field.
void check_settings(const RenderSettings& settings, const SceneLimits& limits);

}  // namespace glint
