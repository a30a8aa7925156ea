#include "scene/environment_map.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace glint {

namespace {

// sin θ at the top edge of row j of `height` (θ = π(1/2 − v), v = j/height).
double sin_latitude_at_row_edge(int j, int height) { return std::sin(kPi * (0.5 - double(j) / height)); }

}  // namespace

EnvironmentMap::EnvironmentMap(int width, int height, std::vector<float> rgb)
    : width_(width), height_(height), rgb_(std::move(rgb)) {
    if (width < 1 || height < 1 || rgb_.size() != size_t(width) * size_t(height) * 3)
        throw std::invalid_argument("environment: width·height RGB texels");
    std::vector<double> luminance(size_t(width) * height), weights(luminance.size());
    for (int j = 0; j < height; ++j)
        for (int i = 0; i < width; ++i) {
            const size_t at = size_t(j) * width + i;
            luminance[at] = cell_weight(i, j);
            weights[at] = luminance[at] * cell_solid_angle(j);
            luminance_integral_ += weights[at];
        }
    // MIS compensation (Karlík et al. 2019): BSDF sampling, combined by MIS, finds the light
    // below the map's mean well enough, so light sampling takes only what stands above it.
    // A map with nothing above its mean (a uniform one) is sampled whole.
    const double mean = luminance_integral_ / (4 * kPi);
    std::vector<double> above(luminance.size());
    double total_above = 0;
    for (int j = 0; j < height; ++j)
        for (int i = 0; i < width; ++i) {
            const size_t at = size_t(j) * width + i;
            above[at] = std::max(luminance[at] - mean, 0.0) * cell_solid_angle(j);
            total_above += above[at];
        }
    distribution_ = Distribution2D(total_above > 0 ? above : weights, width, height);
}

EnvironmentMap EnvironmentMap::from_texture(const Texture& image) {
    const size_t texels = size_t(image.width()) * image.height();
    const int channels = image.channels();
    std::vector<float> rgb(texels * 3);
    for (size_t t = 0; t < texels; ++t)
        for (int c = 0; c < 3; ++c) {
            const size_t at = t * channels + (channels >= 3 ? c : 0);
            rgb[t * 3 + c] = image.is_8bit() ? float(srgb_to_linear(image.bytes()[at])) : image.floats()[at];
        }
    return EnvironmentMap(image.width(), image.height(), std::move(rgb));
}

size_t EnvironmentMap::memory_bytes() const {
    return rgb_.size() * sizeof(float) + distribution_.memory_bytes();
}

double EnvironmentMap::cell_solid_angle(int j) const {
    return 2 * kPi / width_ * (sin_latitude_at_row_edge(j, height_) - sin_latitude_at_row_edge(j + 1, height_));
}

Rgb EnvironmentMap::texel(int i, int j) const {
    i %= width_;
    if (i < 0) i += width_;
    j = std::clamp(j, 0, height_ - 1);
    const float* t = &rgb_[(size_t(j) * width_ + i) * 3];
    return Rgb{t[0], t[1], t[2]};
}

// The mean over texel (i, j)'s cell of the bilinear lookup's luminance: the texel's own weight
// 9/16, its four edge neighbours' 3/32 each, its corners' 1/64 each. Positive wherever a lookup
// in the cell is, so that light sampling misses no light the lookup has.
double EnvironmentMap::cell_weight(int i, int j) const {
    double sum = 0;
    for (int dj = -1; dj <= 1; ++dj)
        for (int di = -1; di <= 1; ++di)
            sum += luminance(texel(i + di, j + dj)) * (di == 0 ? 6 : 1) * (dj == 0 ? 6 : 1);
    return sum / 64;
}

Rgb EnvironmentMap::lookup(double u, double v) const {
    const double x = u * width_ - 0.5, y = v * height_ - 0.5;
    const double fx = std::floor(x), fy = std::floor(y);
    const int i = int(fx), j = int(fy);
    const double ax = x - fx, ay = y - fy;
    const Rgb top = texel(i, j) * (1 - ax) + texel(i + 1, j) * ax;
    const Rgb bottom = texel(i, j + 1) * (1 - ax) + texel(i + 1, j + 1) * ax;
    return top * (1 - ay) + bottom * ay;
}

// Within its cell a point is uniform in solid angle: u uniform, and sin θ uniform between the
// row's edges, so that the density is constant over the cell and finite at the poles.
bool EnvironmentMap::sample(double u1, double u2, double& u, double& z, double& pdf) const {
    if (!(luminance_integral_ > 0)) return false;
    size_t column, row;
    double within_column, within_row;
    distribution_.sample(u1, u2, column, row, within_column, within_row);
    const int j = int(row);
    const double top = sin_latitude_at_row_edge(j, height_), bottom = sin_latitude_at_row_edge(j + 1, height_);
    z = top + (bottom - top) * within_row;
    u = (double(column) + within_column) / width_;
    pdf = cell_pdf(column, row);
    return pdf > 0;
}

double EnvironmentMap::cell_pdf(size_t column, size_t row) const {
    const double probability = distribution_.pdf(column, row) / (double(width_) * height_);
    return probability / cell_solid_angle(int(row));
}

double EnvironmentMap::pdf(double u, double v) const {
    if (!(luminance_integral_ > 0)) return 0;
    const size_t column = std::min(size_t(u * width_), size_t(width_ - 1));
    const size_t row = std::min(size_t(v * height_), size_t(height_ - 1));
    return cell_pdf(column, row);
}

}  // namespace glint
