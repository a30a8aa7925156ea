// Per-pixel accumulation, one round of samples at a time (a round covers the pixel's strata once:
// the tent filter's 2×2 subpixels): the sum of the samples and their count for the mean image,
// and the same for the half of the rounds the sampler draws from its first replicate, for an
// estimate of the mean's error. The sampler gives each pixel two independent replicates of its
// stratified points (sampler.h): the even rounds take theirs from one, the odd rounds from the
// other. The two halves' means are then independent and equally distributed, so the square of
// their difference estimates the variance of the pixel's mean without bias, stratification
// included, where a variance taken over the rounds of one stratified sequence would count its
// strata as noise. Light tracing
// adds splats: contributions a light path makes to pixels other than the one whose sample
// traced it, from any thread. They are summed in 64-bit fixed point, because integer sums do
// not depend on the order of the additions: the image stays bit-identical whatever the thread
// count and however a job is split. Rounding to 2^-32 per splat (splats are in the units of one
// sample of one pixel) is far below what a float PFM keeps.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include "base/image.h"
#include "render/aov.h"

namespace glint {

// Aligned to cache lines: a pixel then spans two lines, not three, and the first holds the
// camera's sums, which only the thread rendering the pixel's tile writes, while the light
// tracer's splats, from any thread, go to the second. Unaligned, two threads' writes would meet
// on shared lines (false sharing); the sums fill the two lines, so alignment costs no memory.
struct alignas(64) PixelSums {
    Rgb sum{0};                // of the samples of the rounds kept
    Rgb half_sum{0};           // of the samples of the rounds kept from the sampler's first replicate
    uint64_t count = 0;        // samples in the rounds kept
    uint64_t half_count = 0;   // of those, samples from the first replicate
    uint64_t dropped = 0;  // samples left out: every sample of a round with a NaN or infinite one
    std::array<int64_t, 3> splat{}, splat_sq{};  // fixed point, see Film::kSplatScale
    uint64_t splats_dropped = 0;                 // non-finite or out of the fixed-point range
};
static_assert(sizeof(PixelSums) == 128 && offsetof(PixelSums, dropped) == 64);

// A pixel's AOV sums (aov.h), over the same samples as its PixelSums' `sum` and `half_sum`, so
// their means share its counts and a denoiser can compare the halves as it does the image's.
struct AovSums {
    Aov sum, half_sum;
};

// Which of a pixel's samples an AOV image averages: all kept, or one replicate's half.
enum class AovHalf { all, first, second };
enum class AovLayer { albedo, normal, depth };

class Film {
public:
    // With `aovs`, the film also keeps each pixel's AOV sums; without, it holds no memory for them.
    Film(int width, int height, bool aovs = false)
        : width_(width), height_(height), pixels_(size_t(width) * height), aovs_(aovs ? pixels_.size() : 0) {}

    int width() const { return width_; }
    int height() const { return height_; }
    bool has_aovs() const { return !aovs_.empty(); }

    // Adds one round of samples to pixel (x, y) (y = 0 is the top row), from the sampler's
    // first replicate if `first_half`; every round of a pixel has the same size. A round with a
    // NaN or infinite component in any sample is dropped whole and its samples counted instead:
    // such a sample would poison the pixel forever, and keeping the rest of its round would
    // weigh the other strata more than its own. `aovs`, one per sample, are kept with the
    // samples when the film has AOVs (and dropped with them).
    void add_round(int x, int y, std::span<const Rgb> samples, bool first_half, std::span<const Aov> aovs = {}) {
        const size_t i = size_t(y) * width_ + x;
        PixelSums& px = pixels_[i];
        for (const Rgb& value : samples)
            if (!is_finite(value)) {
                px.dropped += samples.size();
                return;
            }
        for (const Rgb& value : samples) px.sum += value;
        if (first_half)
            for (const Rgb& value : samples) px.half_sum += value;
        px.count += samples.size();
        if (first_half) px.half_count += samples.size();
        if (!aovs.empty() && has_aovs()) add_aovs(aovs_[i], aovs, first_half);
    }
    // Adds a light-tracing splat to pixel (x, y); thread-safe. `value` is the light path's
    // contribution divided by the number of pixels, so that the splats of one light path per
    // camera sample estimate the pixel as sum / samples per pixel.
    void splat(int x, int y, const Rgb& value);
    static constexpr double kSplatScale = 0x1p32, kSplatSqScale = 0x1p16;
    // The light-traced part of a pixel's mean, and its estimated variance, given
    // samples_per_pixel().
    Rgb splat_mean(const PixelSums& px, double samples_per_pixel) const;
    double splat_variance(const PixelSums& px, int c, double samples_per_pixel) const;
    // Camera samples taken per pixel on average: light paths traced per pixel.
    double samples_per_pixel() const;

    const PixelSums& pixel(int x, int y) const { return pixels_[size_t(y) * width_ + x]; }
    std::vector<PixelSums>& pixels() { return pixels_; }
    const std::vector<PixelSums>& pixels() const { return pixels_; }
    // One per pixel, as pixels(); empty without AOVs.
    std::vector<AovSums>& aovs() { return aovs_; }
    const std::vector<AovSums>& aovs() const { return aovs_; }

    // Adds another film's sums (of other samples of the same image), pixel by pixel; AOV sums
    // too if both have them (a fingerprint tells films with and without apart).
    void merge(const Film& other);

    // The mean of each pixel's samples (0 where it has none yet).
    Image mean() const;
    // The mean of one AOV over each pixel's samples (or one half of them; 0 where there are
    // none), depth in all three channels. An empty image if the film has no AOVs.
    Image aov(AovLayer layer, AovHalf half = AovHalf::all) const;
    Image albedo() const { return aov(AovLayer::albedo); }
    Image normal() const { return aov(AovLayer::normal); }
    Image depth() const { return aov(AovLayer::depth); }
    // Estimated RMSE of mean() against the converged image, in the image's own (linear) units:
    // sqrt of the average over pixels and channels of the variance of the pixel's mean, from
    // the difference of its two halves' means (plus the splats'). Infinite until every pixel
    // has samples in both halves.
    double error_estimate() const;
    // That variance for one pixel and channel, without the splats'; a single pixel's is a
    // one-degree-of-freedom estimate, meant to be averaged over many.
    static double camera_variance(const PixelSums& px, int c);
    uint64_t dropped() const;

private:
    static void add_aovs(AovSums& sums, std::span<const Aov> aovs, bool first_half);

    int width_, height_;
    std::vector<PixelSums> pixels_;
    std::vector<AovSums> aovs_;
};

}  // namespace glint
