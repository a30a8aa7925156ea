// Image textures: texels kept as the file holds them (8-bit for PNG and JPEG, 32-bit linear float
// for .hdr and OpenEXR), and lookups that wrap, filter bilinearly between texel centres and
// decode 8-bit texels to linear values as each use of the texture asks.
#pragma once

#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include "base/math.h"

namespace glint {

// What an 8-bit texel's value means. Colour images are sRGB-encoded; data (roughness, masks,
// normals) are stored as they are. The choice belongs to a use, not to the file: one image can
// be one material's colour and another's data. Float texels are linear whatever a use says.
enum class ColorSpace { srgb, linear };

// The linear value of an sRGB-encoded byte: the exact sRGB EOTF of c = byte/255,
// c <= 0.04045 ? c/12.92 : ((c+0.055)/1.055)^2.4 (what the lookups' table holds).
double srgb_to_linear(uint8_t byte);

class Texture {
public:
    // width·height texels of `channels` (1 to 4) interleaved values, rows top first as image
    // files store them. Throw std::invalid_argument if a size is below 1, channels is not 1..4
    // or the vector does not hold width·height·channels values.
    static Texture from_bytes(int width, int height, int channels, std::vector<uint8_t> texels);
    static Texture from_floats(int width, int height, int channels, std::vector<float> texels);

    int width() const { return width_; }
    int height() const { return height_; }
    int channels() const { return channels_; }
    bool is_8bit() const { return floats_.empty(); }
    size_t memory_bytes() const { return bytes_.size() + floats_.size() * sizeof(float); }
    std::span<const uint8_t> bytes() const { return bytes_; }  // empty for a float texture
    std::span<const float> floats() const { return floats_; }  // empty for an 8-bit texture

private:
    Texture(int width, int height, int channels, std::vector<uint8_t> bytes, std::vector<float> floats);

    int width_, height_, channels_;
    std::vector<uint8_t> bytes_;
    std::vector<float> floats_;
};

// One use of a texture (a material's base colour, its roughness, ...). The texture coordinates
// (u, v) run to the right and up: v = 0 is the image's bottom row, as OBJ and Blender have it.
// A lookup at (u, v) reads the texture at (u·uv_scale[0] + uv_offset[0], v·uv_scale[1] +
// uv_offset[1]), wrapped (repeated) both ways, bilinearly filtered between texel centres (texel
// i from the left, j from the bottom has its centre at ((i+0.5)/width, (j+0.5)/height)): the
// four nearest texels are decoded to linear values first, then weighed. Lookups allocate
// nothing; a NaN or infinite coordinate reads some texel instead of failing.
struct TextureLookup {
    const Texture* texture = nullptr;  // must be set: the lookups do not check
    Rgb scale{1};                      // multiplies the result (glTF's factors)
    double uv_scale[2] = {1, 1};
    double uv_offset[2] = {0, 0};
    ColorSpace colorspace = ColorSpace::srgb;  // for 8-bit colour channels; alpha is always linear
    // -1: the colour; 0..3: r, g, b or a alone. A texel with 1 channel is grey (r = g = b); with
    // 2, grey and alpha; a texture without alpha has a = 1.
    int channel = -1;

    // The colour times scale: for channel -1 the texel's colour (grey for 1 or 2 channels), for
    // channel 0..3 that channel as a grey colour.
    Rgb rgb(double u, double v) const;
    // One value times scale.x: the channel, or for channel -1 the first (r, or the grey).
    double value(double u, double v) const;
};

}  // namespace glint
