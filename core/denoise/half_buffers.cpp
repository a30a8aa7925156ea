#include "denoise/half_buffers.h"

#include "denoise/box_filter.h"

#include <algorithm>

namespace glint {
namespace {

// The filters' squared differences and variances stay finite in float below these (a value
// beyond kMaxValue is a firefly the filters need not see exactly; the unfiltered mean keeps it).
constexpr double kMaxValue = 1e6, kMaxVariance = 1e12;

float bounded(double value) { return float(std::clamp(value, -kMaxValue, kMaxValue)); }

// Fills pixel i of `out` from the film's pixel: its halves' means, and the variance of one
// half's mean from their difference (Film::camera_variance is that of the whole mean).
void split_pixel(const Film& film, const PixelSums& px, double spp, size_t i, HalfBuffers& out) {
    const Rgb splats = film.splat_mean(px, spp);
    const Rgb mean = (px.count > 0 ? px.sum / double(px.count) : Rgb{0}) + splats;
    const double n = double(px.count), n0 = double(px.half_count), n1 = n - n0;
    const bool halves = n0 > 0 && n1 > 0;
    double variance = 0, splat_variance = 0;
    for (int c = 0; c < 3; ++c) {
        out.mean[c][i] = float(mean[c]);
        out.a[c][i] = bounded(halves ? px.half_sum[c] / n0 + splats[c] : mean[c]);
        out.b[c][i] = bounded(halves ? (px.sum[c] - px.half_sum[c]) / n1 + splats[c] : mean[c]);
        splat_variance += film.splat_variance(px, c, spp) / 3.0;
        if (halves) variance += Film::camera_variance(px, c) * n * (1 / n0 + 1 / n1) / 6.0;
    }
    out.half_variance[i] = halves ? float(std::min(variance + splat_variance, kMaxVariance)) : kUnknownVariance;
    out.splat_variance[i] = float(std::min(splat_variance, kMaxVariance));
}

// Each known variance becomes the mean of the known ones in its 3×3 box; unknown ones stay.
void smooth_known(std::vector<float>& variance, int width, int height) {
    std::vector<float> known(variance.size()), masked(variance.size());
    for (size_t i = 0; i < variance.size(); ++i) {
        known[i] = variance[i] < kUnknownVariance ? 1.0f : 0.0f;
        masked[i] = known[i] > 0 ? variance[i] : 0.0f;
    }
    const std::vector<float> sums = box_filter(masked, width, height, 1);
    const std::vector<float> counts = box_filter(known, width, height, 1);
    for (size_t i = 0; i < variance.size(); ++i)
        if (known[i] > 0) variance[i] = std::max(0.0f, sums[i] / counts[i]);
}

}  // namespace

HalfBuffers half_buffers(const Film& film) {
    HalfBuffers out;
    out.width = film.width();
    out.height = film.height();
    const size_t pixels = size_t(out.width) * out.height;
    for (int c = 0; c < 3; ++c) out.mean[c].resize(pixels), out.a[c].resize(pixels), out.b[c].resize(pixels);
    out.half_variance.resize(pixels);
    out.splat_variance.resize(pixels);
    const double spp = film.samples_per_pixel();
    for (size_t i = 0; i < pixels; ++i) split_pixel(film, film.pixels()[i], spp, i, out);
    smooth_known(out.half_variance, out.width, out.height);
    return out;
}

}  // namespace glint
