// Image files as textures, told apart by their content: PNG, JPEG and the other 8-bit formats
// stb_image reads (BMP, TGA, GIF's first frame, PSD, PIC, PNM) stay 8-bit; Radiance .hdr and
// OpenEXR become linear 32-bit floats.
#pragma once

#include <cstddef>
#include <cstdint>
#include <stdexcept>
#include <string>
#include <vector>

#include "scene/texture.h"

namespace glint {

// What is wrong with a texture file; the message names the file.
struct TextureError : std::runtime_error {
    using std::runtime_error::runtime_error;
};

struct TextureLimits {
    // 8192 × 8192: 256 MiB as 8-bit RGBA, 1 GiB as float RGBA. A loader that bounds a scene's
    // total passes what it has left, when that is less: the size is checked from the file's
    // header, before anything of that size is allocated.
    size_t max_texels_per_file = size_t(1) << 26;
};

struct DecodedTexture {
    Texture texture;
    // Float values below zero (lossy EXR compression undershoots near black) set to 0, for the
    // caller to warn about.
    size_t negative_values = 0;
};

// Throws TextureError, naming the file by `name`, if an image of width × height texels is more
// than `limits` allow.
void check_texture_size(const std::string& name, int64_t width, int64_t height, const TextureLimits& limits);

// The texture in `bytes`, rows top first as the file stores them. 16-bit PNGs are read as 8-bit
// (stb_image rounds them), so their colour space stays a lookup's choice. From an EXR file it
// reads the data window's R, G, B (a missing one is 0) and A, or else Y and A: 3, 4, 1 or 2
// channels. Throws TextureError, naming the file by `name`, for what is not an image it reads,
// is truncated or corrupt, has more texels than `limits` allow, or holds a NaN or infinite value.
DecodedTexture decode_texture(const std::vector<uint8_t>& bytes, const std::string& name,
                              const TextureLimits& limits = {});

}  // namespace glint
