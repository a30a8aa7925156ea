// OpenEXR output (through the OpenEXR library): one scanline file of 32-bit float channels,
// linear, losslessly (ZIP) compressed, rows top to bottom. Channels are named as Nuke and
// Blender read layers, "layer.channel": the image is R, G, B; a film adds sample_count.Y and
// variance.R/G/B, and with AOVs albedo.R/G/B, N.X/Y/Z and Z (depth); README lists them. A caller
// adds a layer of its own (a denoised image, say) by appending one more ExrLayer.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "base/image.h"
#include "render/film.h"

namespace glint {

struct ExrLayer {
    std::string name;                        // "" for channels without a layer (R, G, B, Z)
    std::vector<std::string> channels;       // the file names channel c "name.channels[c]"
    std::vector<std::vector<float>> planes;  // one per channel, width·height values, rows top to bottom
};

// The first channels.size() channels of `image` as a layer.
ExrLayer exr_layer(std::string name, const Image& image, std::vector<std::string> channels = {"R", "G", "B"});

// What a film keeps per pixel besides its mean image: the samples each pixel's mean averages
// (sample_count.Y), the estimated variance of that mean (variance.R/G/B: Film::camera_variance
// plus the splats' Film::splat_variance; 0 where it cannot be estimated yet, a pixel without
// samples in both halves), and the AOVs' means if it has them (albedo.R/G/B, N.X/Y/Z, Z).
std::vector<ExrLayer> film_layers(const Film& film);

// An EXR of a film: `image` (its mean, as R, G, B), film_layers(film), then `extra` (such as the
// denoised preview).
std::vector<uint8_t> encode_film_exr(const Image& image, const Film& film, std::vector<ExrLayer> extra = {});

// The file's bytes; throws std::invalid_argument if a plane is not width·height values or two
// channels have one name, and std::runtime_error if OpenEXR cannot write it.
std::vector<uint8_t> encode_exr(int width, int height, const std::vector<ExrLayer>& layers);

}  // namespace glint
