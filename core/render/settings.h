// What a render is asked for: image size, samples, filter, sampler, seed and stop conditions.
// Plain data, so the scene loader and the fingerprint can name a render without the renderer.
#pragma once

#include <algorithm>
#include <cstdint>

#include "base/image.h"
#include "render/filter.h"
#include "render/sampler.h"

namespace glint {

// A window of the image, in pixels with rows from the top (as in the PNG): [x0, x1) × [y0, y1).
// A region job renders only the window, each pixel exactly as a render of the whole image would.
struct Region {
    int x0 = 0, y0 = 0, x1 = 0, y1 = 0;
    int width() const { return x1 - x0; }
    int height() const { return y1 - y0; }
    bool contains(int x, int y) const { return x >= x0 && x < x1 && y >= y0 && y < y1; }
    bool operator==(const Region&) const = default;
    bool empty() const { return x0 >= x1 || y0 >= y1; }
};

// The pixels in both; empty() if they do not meet.
inline Region intersection(const Region& a, const Region& b) {
    return {std::max(a.x0, b.x0), std::max(a.y0, b.y0), std::min(a.x1, b.x1), std::min(a.y1, b.y1)};
}

struct RenderSettings {
    int width = 1024, height = 768;  // of the whole image, also for a region job
    // Empty (all zero): the whole image. Otherwise the window that is rendered and stored.
    Region region;
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
    // Whether the film also averages the camera paths' AOVs (render/aov.h: albedo, normal,
    // depth) for an EXR or a denoiser; off, they cost nothing.
    bool aovs = false;

    bool whole_image() const { return region == Region{}; }
    // The pixels rendered: the region, or the whole image.
    Region window() const { return whole_image() ? Region{0, 0, width, height} : region; }
};

}  // namespace glint
