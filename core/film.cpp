#include "film.h"

namespace glint {

Image Film::mean() const {
    Image image(width_, height_);
    for (int y = 0; y < height_; ++y)
        for (int x = 0; x < width_; ++x) {
            const PixelSums& px = pixel(x, y);
            if (px.count > 0) image.set(x, y, px.sum / double(px.count));
        }
    return image;
}

double Film::error_estimate() const {
    double total = 0;
    for (const PixelSums& px : pixels_) {
        if (px.count < 2) return kInfinity;  // no variance without two samples
        const double n = double(px.count);
        for (int c = 0; c < 3; ++c) {
            const double variance = std::max(0.0, (px.sum_sq[c] - px.sum[c] * px.sum[c] / n) / (n - 1));
            total += variance / n;
        }
    }
    return std::sqrt(total / (3.0 * double(pixels_.size())));
}

void Film::merge(const Film& other) {
    for (size_t i = 0; i < pixels_.size(); ++i) {
        PixelSums& px = pixels_[i];
        const PixelSums& o = other.pixels_[i];
        px.sum += o.sum;
        px.sum_sq += o.sum_sq;
        px.count += o.count;
        px.dropped += o.dropped;
    }
}

uint64_t Film::dropped() const {
    uint64_t total = 0;
    for (const PixelSums& px : pixels_) total += px.dropped;
    return total;
}

}  // namespace glint
