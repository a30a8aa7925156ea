// Non-local means for rendered images (Rousselle, Knaus and Zwicker 2012, "Adaptive rendering
// with non-local means filtering"): each pixel becomes a weighted mean of the pixels in a window
// around it, a neighbour weighing by how alike the patches around the two are, their squared
// difference less what the two pixels' noise makes and measured in units of the filtered pixel's
// own noise; with
// features (Rousselle, Manzi and Zwicker 2013), a neighbour also weighs by how alike its features
// are, and its weight is the lesser of the two. Several candidates at once: they share the
// distances.
#pragma once

#include <array>
#include <vector>

#include "base/thread_pool.h"
#include "denoise/denoiser_config.h"

namespace glint {

using Planes = std::array<std::vector<float>, 3>;  // per channel, width × height, rows top first

struct NlMeansInput {
    int width = 0, height = 0;
    const Planes* image;                   // what is filtered, and what the weights compare
    const std::vector<float>* variance;    // per pixel, of the image (kUnknownVariance: unknown)
    // Null, or kFeatures planes and their variances (half_buffers.h); needed by the candidates
    // with a feature strength.
    const std::vector<std::vector<float>>* features = nullptr;
    const std::vector<std::vector<float>>* feature_variance = nullptr;
};

struct NlMeansOutput {
    std::vector<Planes> filtered;  // one per candidate of the filter
};

// The filter's candidates, with the config's variance_cancel and feature_floor. Deterministic:
// each pixel's sums are added in one fixed order, whatever the pool's size.
NlMeansOutput nl_means(const NlMeansInput& input, const DenoiserConfig::Filter& filter, const DenoiserConfig& config,
                       ThreadPool& pool);

}  // namespace glint
