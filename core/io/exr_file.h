// OpenEXR output (through the OpenEXR library): one scanline file of 32-bit float channels,
// linear, losslessly (ZIP) compressed, rows top to bottom. Channels are named as Nuke and
// Blender read layers, "layer.channel": an image is R, G, B; a film's layers are
// assembly/film_exr.h's. A caller adds a layer of its own (a denoised image, say) by appending
// one more ExrLayer.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "base/image.h"

namespace glint {

struct ExrLayer {
    std::string name;                        // "" for channels without a layer (R, G, B, Z)
    std::vector<std::string> channels;       // the file names channel c "name.channels[c]"
    std::vector<std::vector<float>> planes;  // one per channel, width·height values, rows top to bottom
};

// The first channels.size() channels of `image` as a layer.
ExrLayer exr_layer(std::string name, const Image& image, std::vector<std::string> channels = {"R", "G", "B"});

// The file's bytes; throws std::invalid_argument if a plane is not width·height values or two
// channels have one name, and std::runtime_error if OpenEXR cannot write it.
std::vector<uint8_t> encode_exr(int width, int height, const std::vector<ExrLayer>& layers);

}  // namespace glint
