// Image files: 8-bit PNG (through stb_image_write) and linear float PFM.
#pragma once

#include <cstdint>
#include <stdexcept>
#include <string>
#include <vector>

#include "base/image.h"

namespace glint {

struct ImageError : std::runtime_error {
    using std::runtime_error::runtime_error;
};

uint8_t encode_value(double linear, Encoding encoding);

std::vector<uint8_t> encode_png(const Image& image, Encoding encoding);
// PFM (Portable Float Map), colour, little-endian; rows stored bottom to top as the format says.
std::vector<uint8_t> encode_pfm(const Image& image);
Image decode_pfm(const std::vector<uint8_t>& bytes);

}  // namespace glint
