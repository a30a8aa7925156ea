// First-order regression on features, the model of NFOR (Bitterli et al. 2016, "Nonlinearly
// weighted first-order regression for denoising Monte Carlo renderings"): around pixel p, the
// colour of each neighbour q is fitted as a + bᵀ(f_q − f_p), f the pixel's features (albedo,
// normal, depth), by least squares weighted with q's non-local means weight; the pixel becomes
// the intercept a. Where the weights' mean blurs across a change of albedo, normal or depth
// inside the window, the fit follows it, so the window may take neighbours the mean could not.
#pragma once

#include <array>
#include <vector>

#include "denoise/half_buffers.h"

namespace glint {

// The weighted normal equations of one band of pixels.
class RegressionSums {
public:
    static constexpr int kTerms = 1 + kFeatures;  // the intercept and one slope per feature plane
    explicit RegressionSums(size_t pixels) : sums_(pixels * kStride, 0.0) {}

    // Adds neighbour q to pixel i's fit with weight w: its features' differences from the
    // pixel's, `delta`, and its colour.
    void add(size_t i, double w, const std::array<float, kFeatures>& delta, const std::array<float, 3>& colour);
    // The fitted intercept per channel, or false where the system cannot be solved (no weight,
    // or a value not finite): the caller keeps the weighted mean then.
    bool solve(size_t i, std::array<float, 3>& colour) const;

private:
    // Per pixel: the upper triangle of Σ w x xᵀ, then Σ w x y per channel, x = (1, delta).
    static constexpr int kMatrix = kTerms * (kTerms + 1) / 2, kStride = kMatrix + 3 * kTerms;
    std::vector<double> sums_;
};

}  // namespace glint
