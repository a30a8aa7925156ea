// What the denoiser reads from a film: the image, the means of its two independent halves
// (film.h: the rounds from the sampler's first replicate, and the others) and each pixel's
// variance, as planar float images.
#pragma once

#include <array>
#include <vector>

#include "render/film.h"

namespace glint {

struct HalfBuffers {
    int width = 0, height = 0;
    // Per channel, width × height floats, rows top first. The light tracer's splats have no
    // halves: both halves carry them whole, so a - b is the camera samples' noise only.
    std::array<std::vector<float>, 3> mean, a, b;
    // Per pixel, averaged over the channels: the variance of one half's mean (camera samples
    // and splats), smoothed over 3×3 pixels (one pixel's estimate has one degree of freedom per
    // channel); and the splats' part alone, which a - b does not show.
    std::vector<float> half_variance, splat_variance;
};

// A pixel that has no samples in one of its halves yet (the first round) gets the mean in both
// and a variance of kUnknownVariance: the filters then leave it as it is.
HalfBuffers half_buffers(const Film& film);
inline constexpr float kUnknownVariance = 1e20f;

}  // namespace glint
