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
    const Rgb mean = px.count > 0 ? px.sum / double(px.count) : Rgb{0};
    const double n = double(px.count), n0 = double(px.half_count), n1 = n - n0;
    const bool halves = n0 > 0 && n1 > 0;
    double variance = 0;
    for (int c = 0; c < 3; ++c) {
        out.mean[c][i] = float(mean[c]);
        out.splats[c][i] = float(splats[c]);
        out.a[c][i] = bounded(halves ? px.half_sum[c] / n0 : mean[c]);
        out.b[c][i] = bounded(halves ? (px.sum[c] - px.half_sum[c]) / n1 : mean[c]);
        if (halves) variance += Film::camera_variance(px, c) * n * (1 / n0 + 1 / n1) / 6.0;
    }
    out.half_variance[i] = halves ? float(std::min(variance, kMaxVariance)) : kUnknownVariance;
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

// One half's features as planes: albedo, normal, depth scaled by `depth_scale`.
std::vector<std::vector<float>> feature_planes(const Film& film, AovHalf half, double depth_scale) {
    std::vector<std::vector<float>> planes;
    for (AovLayer layer : {AovLayer::albedo, AovLayer::normal, AovLayer::depth}) {
        const Image image = film.aov(layer, half);
        for (int c = 0; c < (layer == AovLayer::depth ? 1 : 3); ++c) {
            std::vector<float>& plane = planes.emplace_back(image.rgb.size() / 3);
            const float scale = layer == AovLayer::depth ? float(depth_scale) : 1.0f;
            for (size_t i = 0; i < plane.size(); ++i) plane[i] = image.rgb[i * 3 + c] * scale;
        }
    }
    return planes;
}

void add_features(const Film& film, HalfBuffers& out) {
    const Image depth = film.depth();
    const float deepest = *std::max_element(depth.rgb.begin(), depth.rgb.end());
    const double scale = deepest > 0 ? 1.0 / deepest : 1.0;
    out.features_a = feature_planes(film, AovHalf::first, scale);
    out.features_b = feature_planes(film, AovHalf::second, scale);
    for (int j = 0; j < kFeatures; ++j) {
        std::vector<float>& variance = out.feature_variance.emplace_back(out.features_a[j].size());
        for (size_t i = 0; i < variance.size(); ++i) {
            const float d = out.features_a[j][i] - out.features_b[j][i];
            variance[i] = out.half_variance[i] < kUnknownVariance ? d * d / 2 : kUnknownVariance;
        }
        smooth_known(variance, out.width, out.height);
    }
}

}  // namespace

HalfBuffers half_buffers(const Film& film) {
    HalfBuffers out;
    out.width = film.width();
    out.height = film.height();
    const size_t pixels = size_t(out.width) * out.height;
    for (int c = 0; c < 3; ++c)
        out.mean[c].resize(pixels), out.a[c].resize(pixels), out.b[c].resize(pixels), out.splats[c].resize(pixels);
    out.half_variance.resize(pixels);
    const double spp = film.samples_per_pixel();
    for (size_t i = 0; i < pixels; ++i) split_pixel(film, film.pixels()[i], spp, i, out);
    smooth_known(out.half_variance, out.width, out.height);
    if (film.has_aovs() && pixels > 0) add_features(film, out);
    return out;
}

}  // namespace glint
