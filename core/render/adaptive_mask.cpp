#include "render/adaptive_mask.h"

#include <algorithm>
#include <cmath>

namespace glint {
namespace {

// Keeps a black image (no spread, no level) from dividing by zero; far below any visible level.
constexpr double kLevelFloor = 1e-4;

uint32_t round_up(uint32_t value, uint32_t step) { return (value + step - 1) / step * step; }

double scaled_threshold(const AdaptiveSettings& s, uint32_t spp) {
    return s.job_spp > spp ? s.threshold * std::sqrt(double(s.job_spp) / double(spp)) : s.threshold;
}

uint32_t automatic_min_spp(double threshold) {
    const double wanted = threshold > 0 ? std::ceil(4 / std::sqrt(threshold)) : 0;
    return round_up(uint32_t(std::clamp(wanted, double(AdaptiveMask::kCheckInterval), 65536.0)),
                    AdaptiveMask::kCheckInterval);
}

}  // namespace

AdaptiveMask::AdaptiveMask(const AdaptiveSettings& settings, uint32_t spp, int width, int height)
    : threshold_(scaled_threshold(settings, spp)),
      min_spp_(settings.min_spp > 0 ? settings.min_spp : automatic_min_spp(threshold_)),
      width_(width),
      height_(height),
      converged_(size_t(width) * size_t(height), 0),
      active_(converged_.size(), 1),
      active_count_(converged_.size()) {}

double AdaptiveMask::spread(const PixelSums& px) {
    double sum = 0;
    for (int c = 0; c < 3; ++c) sum += std::sqrt(Film::camera_variance(px, c));
    return sum;
}

double AdaptiveMask::level(const Film& film) {
    double sum = 0;
    for (const PixelSums& px : film.pixels())
        if (px.count > 0) sum += (px.sum[0] + px.sum[1] + px.sum[2]) / double(px.count);
    return sum / double(film.pixels().size());
}

void AdaptiveMask::update(const Film& film) {
    const std::vector<PixelSums>& pixels = film.pixels();
    const double scale = 1 / (kLevelFloor + std::sqrt(std::max(0.0, level(film))));
    for (size_t i = 0; i < pixels.size(); ++i)
        converged_[i] = pixels[i].count + pixels[i].dropped >= min_spp_ && spread(pixels[i]) * scale < threshold_;
    dilate();
}

void AdaptiveMask::dilate() {
    active_count_ = 0;
    for (int y = 0; y < height_; ++y)
        for (int x = 0; x < width_; ++x) {
            bool any = false;
            for (int ny = std::max(0, y - 1); ny <= std::min(height_ - 1, y + 1); ++ny)
                for (int nx = std::max(0, x - 1); nx <= std::min(width_ - 1, x + 1); ++nx)
                    any = any || !converged_[size_t(ny) * size_t(width_) + size_t(nx)];
            active_[size_t(y) * size_t(width_) + size_t(x)] = any;
            active_count_ += any;
        }
}

}  // namespace glint
