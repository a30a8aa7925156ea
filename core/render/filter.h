// Pixel filters: how a sample of pixel (x, y) picks its film position, and the density of that
// choice, which light tracing needs to splat a film position onto the pixels that could have
// sampled it (the same weight as the camera's, so both estimate the same pixel values).
#pragma once

#include <cmath>
#include <cstdint>

#include "base/sampling.h"

namespace glint {

// tent: smallpt's 2×2 subpixels with tent-distributed offsets; sample s goes to subpixel s mod 4,
// so sample counts are whole multiples of 4. box: uniform over the pixel.
enum class Filter { tent, box };

inline uint32_t samples_per_round(Filter f) { return f == Filter::tent ? 4 : 1; }
constexpr uint32_t kMaxSamplesPerRound = 4;

// Film offset within the pixel (0 at its left or bottom edge) of sample `index` along one axis;
// `subpixel` is 0 or 1 (smallpt's sx or sy).
inline double filter_offset(Filter f, uint32_t subpixel, double u) {
    return f == Filter::tent ? (subpixel + 0.5 + sample_tent(u)) / 2 : u;
}

// How far outside [0, 1] a pixel's samples can land: the tent's footprint is [-0.25, 1.25].
inline double filter_margin(Filter f) { return f == Filter::tent ? 0.25 : 0; }

// Density (per unit film area in pixels) of a sample of a pixel landing at offset (dx, dy) from
// the pixel's corner, averaged over the samples of a round. Integrates to 1 over the footprint.
inline double filter_density(Filter f, double dx, double dy) {
    if (f == Filter::box) return dx >= 0 && dx < 1 && dy >= 0 && dy < 1 ? 1 : 0;
    // Subpixel centres at 0.25 and 0.75; each offset is tent(u)/2, a density 2·(1 - |2·d|).
    auto tent = [](double d) { return std::max(0.0, 2 * (1 - std::fabs(2 * d))); };
    const double x = tent(dx - 0.25) + tent(dx - 0.75), y = tent(dy - 0.25) + tent(dy - 0.75);
    return x * y / 4;
}

}  // namespace glint
