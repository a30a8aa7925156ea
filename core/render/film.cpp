#include "render/film.h"

#include <atomic>

namespace glint {
namespace {

// value·scale rounded, or false if it does not fit in an int64 (or is not finite).
bool to_fixed(double value, double scale, int64_t& out) {
    const double scaled = std::nearbyint(value * scale);
    if (!(std::fabs(scaled) < 0x1p62)) return false;
    out = static_cast<int64_t>(scaled);
    return true;
}

void add(Aov& to, const Aov& a) {
    to.albedo += a.albedo;
    to.normal += a.normal;
    to.depth += a.depth;
}

// One AOV of `a` as a colour (depth in every channel).
Rgb layer_of(const Aov& a, AovLayer layer) {
    switch (layer) {
        case AovLayer::albedo: return a.albedo;
        case AovLayer::normal: return a.normal;
        case AovLayer::depth: return Rgb{a.depth};
    }
    return Rgb{0};
}

}  // namespace

void Film::add_aovs(AovSums& sums, std::span<const Aov> aovs, bool first_half) {
    for (const Aov& a : aovs) add(sums.sum, a);
    if (first_half)
        for (const Aov& a : aovs) add(sums.half_sum, a);
}

Image Film::aov(AovLayer layer, AovHalf half) const {
    if (!has_aovs()) return Image();
    Image image(width_, height_);
    for (size_t i = 0; i < pixels_.size(); ++i) {
        const PixelSums& px = pixels_[i];
        const Rgb all = layer_of(aovs_[i].sum, layer), first = layer_of(aovs_[i].half_sum, layer);
        const uint64_t n = half == AovHalf::all ? px.count : half == AovHalf::first ? px.half_count
                                                                                      : px.count - px.half_count;
        const Rgb sum = half == AovHalf::all ? all : half == AovHalf::first ? first : all - first;
        if (n > 0) image.set(int(i % width_), int(i / width_), sum / double(n));
    }
    return image;
}

void Film::splat(int x, int y, const Rgb& value) {
    PixelSums& px = pixels_[size_t(y) * width_ + x];
    std::array<int64_t, 3> v, v2;
    for (int c = 0; c < 3; ++c)
        if (!to_fixed(value[c], kSplatScale, v[c]) || !to_fixed(value[c] * value[c], kSplatSqScale, v2[c])) {
            std::atomic_ref<uint64_t>(px.splats_dropped).fetch_add(1, std::memory_order_relaxed);
            return;
        }
    for (int c = 0; c < 3; ++c) {
        std::atomic_ref<int64_t>(px.splat[c]).fetch_add(v[c], std::memory_order_relaxed);
        std::atomic_ref<int64_t>(px.splat_sq[c]).fetch_add(v2[c], std::memory_order_relaxed);
    }
}

double Film::samples_per_pixel() const {
    uint64_t samples = 0;
    for (const PixelSums& px : pixels_) samples += px.count + px.dropped;
    return double(samples) / double(pixels_.size());
}

Rgb Film::splat_mean(const PixelSums& px, double n) const {
    if (px.splat == std::array<int64_t, 3>{}) return Rgb{0};
    return Rgb{double(px.splat[0]), double(px.splat[1]), double(px.splat[2])} / (kSplatScale * n);
}

// Each of the N = pixels·n light paths contributes X to this pixel (mostly 0), and the pixel's
// light-traced part is ΣX/N, with variance (ΣX²/N - mean²)/N. The sums hold X/pixels.
double Film::splat_variance(const PixelSums& px, int c, double n) const {
    if (px.splat_sq[c] == 0) return 0;
    const double pixels = double(pixels_.size());
    const double mean = double(px.splat[c]) / (kSplatScale * n);
    const double mean_sq = pixels * double(px.splat_sq[c]) / (kSplatSqScale * n);
    return std::max(0.0, mean_sq - mean * mean) / (pixels * n);
}

Image Film::mean() const {
    Image image(width_, height_);
    const double n = samples_per_pixel();
    for (int y = 0; y < height_; ++y)
        for (int x = 0; x < width_; ++x) {
            const PixelSums& px = pixel(x, y);
            const Rgb camera = px.count > 0 ? px.sum / double(px.count) : Rgb{0};
            image.set(x, y, camera + splat_mean(px, n));
        }
    return image;
}

// The halves' means m0 = S0/n0 and m1 = S1/n1 are independent, with variances V/n0 and V/n1
// for some V (each half is a stratified replicate of the same points, dropped rounds aside).
// The pixel's mean (S0 + S1)/n has variance V/n, and E[(m0 − m1)²] = V·n/(n0·n1), so
// (m0 − m1)²·n0·n1/n² estimates it without bias: (m0 − m1)²/4 for equal halves.
double Film::camera_variance(const PixelSums& px, int c) {
    const double n = double(px.count), n0 = double(px.half_count), n1 = n - n0;
    if (n0 == 0 || n1 == 0) return kInfinity;  // no variance without both halves
    const double d = px.half_sum[c] / n0 - (px.sum[c] - px.half_sum[c]) / n1;
    return d * d * n0 * n1 / (n * n);
}

double Film::error_estimate() const {
    double total = 0;
    const double spp = samples_per_pixel();
    for (const PixelSums& px : pixels_)
        for (int c = 0; c < 3; ++c) total += camera_variance(px, c) + splat_variance(px, c, spp);
    return std::sqrt(total / (3.0 * double(pixels_.size())));
}

void Film::merge(const Film& other) {
    for (size_t i = 0; i < pixels_.size(); ++i) {
        PixelSums& px = pixels_[i];
        const PixelSums& o = other.pixels_[i];
        px.sum += o.sum;
        px.half_sum += o.half_sum;
        px.count += o.count;
        px.half_count += o.half_count;
        px.dropped += o.dropped;
        for (int c = 0; c < 3; ++c) {
            px.splat[c] += o.splat[c];
            px.splat_sq[c] += o.splat_sq[c];
        }
        px.splats_dropped += o.splats_dropped;
    }
    if (has_aovs() && other.has_aovs())
        for (size_t i = 0; i < aovs_.size(); ++i) {
            add(aovs_[i].sum, other.aovs_[i].sum);
            add(aovs_[i].half_sum, other.aovs_[i].half_sum);
        }
}

uint64_t Film::dropped() const {
    uint64_t total = 0;
    for (const PixelSums& px : pixels_) total += px.dropped + px.splats_dropped;
    return total;
}

}  // namespace glint
