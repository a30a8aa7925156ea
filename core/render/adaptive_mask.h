// Adaptive sampling: which pixels of the film still receive camera samples. Decided every
// kCheckInterval samples, between passes, from the film's camera sums alone (a pure function of
// them), so a render's mask never depends on thread count, pass sizes or timing, and a job
// resumed from a checkpoint recomputes the mask its uninterrupted run had.
//
// A pixel has converged once it has min_spp samples and its error (spread) relative to the
// image's level is below the threshold; it is active unless it and its 8 neighbours have all converged (the 3×3
// dilation: a pixel's one-degree-of-freedom error estimate is noisy, and a converged-looking pixel
// beside a noisy one is likely noisy too). The film's light-tracing splats play no part.
#pragma once

#include <cstdint>
#include <vector>

#include "render/film.h"
#include "render/settings.h"

namespace glint {

class AdaptiveMask {
public:
    // Samples between decisions: a multiple of every filter's round (filter.h).
    static constexpr uint32_t kCheckInterval = 16;

    // For a render of `spp` samples of a `width` × `height` film: every pixel starts active.
    AdaptiveMask(const AdaptiveSettings& settings, uint32_t spp, int width, int height);

    // The pixel's estimated error Σ_c σ_c, σ_c the standard deviation of the pixel's mean from
    // its two halves (Film::camera_variance); infinite without samples in both halves. The mask
    // compares spread / sqrt(level) with the threshold: Cycles' form (its error is the pixel's
    // spread over the square root of the pixel's own brightness), with the image's level in
    // place of the pixel's, so that the threshold does not depend on the exposure while every
    // pixel stops at the same absolute error, which is what the image's RMSE weighs
    // (docs/adaptive.md: the pixel's own brightness spent samples on dark pixels).
    static double spread(const PixelSums& px);
    // Σ_c mean_c averaged over the film's pixels (those without samples count 0).
    static double level(const Film& film);

    // The threshold this render compares against: the setting's, scaled by sqrt(job_spp / spp)
    // for a part of a job (its error is sqrt(parts) times the merged image's).
    double threshold() const { return threshold_; }
    // The samples before any pixel stops: the setting's, or automatically about 4/sqrt(threshold)
    // (a lower threshold trusts fewer samples less), at least one check interval.
    uint32_t min_spp() const { return min_spp_; }

    // Decides from the film's sums (call between passes, at multiples of kCheckInterval).
    void update(const Film& film);
    bool active(int x, int y) const { return active_[size_t(y) * size_t(width_) + size_t(x)] != 0; }
    size_t active_pixels() const { return active_count_; }

private:
    void dilate();

    double threshold_;
    uint32_t min_spp_;
    int width_, height_;
    std::vector<uint8_t> converged_, active_;  // a byte per pixel: read by every tile's pixel loop
    size_t active_count_;
};

}  // namespace glint
