// Non-local means for rendered images (Rousselle, Knaus and Zwicker 2012, "Adaptive rendering
// with non-local means filtering"): each pixel becomes a weighted mean of the pixels in a window
// around it, a neighbour weighing by how alike the patches around the two are, their squared
// difference less what the two pixels' noise makes and measured in units of that noise. Several
// strengths at once: they share the patch distances.
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
};

struct NlMeansOutput {
    std::vector<Planes> filtered;                 // one per strength in the config
    std::vector<std::vector<float>> self_weight;  // per strength: the pixel's own share of its mean
};

// Deterministic: each pixel's sums are added in one fixed order, whatever the pool's size.
NlMeansOutput nl_means(const NlMeansInput& input, const DenoiserConfig& config, ThreadPool& pool);

}  // namespace glint
