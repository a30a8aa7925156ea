// What a render is asked for: image size, samples, filter, sampler, seed and stop conditions.
// Plain data, so the scene loader and the fingerprint can name a render without the renderer.
#pragma once

#include <cstdint>

#include "base/image.h"
#include "render/filter.h"
#include "render/sampler.h"

namespace glint {

struct RenderSettings {
    int width = 1024, height = 768;
    uint32_t spp = 64;  // rounded up to a multiple of samples_per_round(filter)
    // Renders samples [first_sample, first_sample + spp) of every pixel: a part of a job split
    // over machines. Must be a multiple of samples_per_round(filter).
    uint32_t first_sample = 0;
    Filter filter = Filter::tent;
    Sampler sampler = Sampler::sobol;
    uint64_t seed = 0;
    Encoding encoding = Encoding::gamma22;
    double target_error = 0;  // stop once error_estimate() <= this; 0 = off
    double time_limit = 0;    // seconds; 0 = off
};

}  // namespace glint
