#include "assembly/film_exr.h"

#include <cmath>

namespace glint {
namespace {

// The variance of each pixel's mean in channel c, finite (0 where it is unknown).
float pixel_variance(const Film& film, const PixelSums& px, int c, double spp) {
    const double v = Film::camera_variance(px, c) + film.splat_variance(px, c, spp);
    return std::isfinite(v) ? float(v) : 0.0f;
}

}  // namespace

std::vector<ExrLayer> film_layers(const Film& film) {
    const size_t pixels = film.pixels().size();
    ExrLayer count{"sample_count", {"Y"}, {std::vector<float>(pixels)}};
    ExrLayer variance{"variance", {"R", "G", "B"}, std::vector<std::vector<float>>(3, std::vector<float>(pixels))};
    const double spp = film.samples_per_pixel();
    for (size_t i = 0; i < pixels; ++i) {
        const PixelSums& px = film.pixels()[i];
        count.planes[0][i] = float(px.count);
        for (int c = 0; c < 3; ++c) variance.planes[size_t(c)][i] = pixel_variance(film, px, c, spp);
    }
    std::vector<ExrLayer> layers{std::move(count), std::move(variance)};
    if (film.has_aovs()) {
        layers.push_back(exr_layer("albedo", film.albedo()));
        layers.push_back(exr_layer("N", film.normal(), {"X", "Y", "Z"}));
        layers.push_back(exr_layer("", film.depth(), {"Z"}));
    }
    return layers;
}

std::vector<uint8_t> encode_film_exr(const Image& image, const Film& film, std::vector<ExrLayer> extra) {
    std::vector<ExrLayer> layers = film_layers(film);
    layers.insert(layers.begin(), exr_layer("", image));
    for (ExrLayer& layer : extra) layers.push_back(std::move(layer));
    return encode_exr(image.width, image.height, layers);
}

}  // namespace glint
