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
    // Per channel, width × height floats, rows top first: the camera samples' mean and its two
    // halves' means, and the light tracer's splats. The splats have no halves, so nothing can
    // tell their noise from their signal: the denoiser leaves them as they are and adds them
    // back (a caustic they draw is never smeared).
    std::array<std::vector<float>, 3> mean, a, b, splats;
    // Per pixel, averaged over the channels: the variance of one half's mean, smoothed over 3×3
    // pixels (one pixel's estimate has one degree of freedom per channel).
    std::vector<float> half_variance;
    // With the film's AOVs (empty without): per half, the features the filters may compare
    // (albedo, normal, and depth over the image's largest: kFeatures planes), and each plane's
    // variance of a half's mean, from the halves' difference, smoothed as the image's.
    std::vector<std::vector<float>> features_a, features_b, feature_variance;
    bool has_features() const { return !features_a.empty(); }
};
inline constexpr int kFeatures = 7;

// A pixel that has no samples in one of its halves yet (the first round) gets the mean in both
// and a variance of kUnknownVariance: the filters then leave it as it is.
HalfBuffers half_buffers(const Film& film);
inline constexpr float kUnknownVariance = 1e20f;

}  // namespace glint
