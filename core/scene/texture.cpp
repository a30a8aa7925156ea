#include "scene/texture.h"

#include <array>
#include <cmath>
#include <stdexcept>
#include <string>

namespace glint {
namespace {

using DecodeTable = std::array<double, 256>;

template <typename Decode>
DecodeTable make_table(Decode decode) {
    DecodeTable table{};
    for (int b = 0; b < 256; ++b) table[size_t(b)] = decode(b / 255.0);
    return table;
}

// Tables, so a lookup decodes a byte with one load whichever the colour space, and the sRGB
// curve's pow() runs 256 times per process instead of four times a channel per lookup.
const DecodeTable kSrgb =
    make_table([](double c) { return c <= 0.04045 ? c / 12.92 : std::pow((c + 0.055) / 1.055, 2.4); });
const DecodeTable kUnit = make_table([](double c) { return c; });

// One axis of a lookup: the two texels either side of the position and the second's weight.
struct Axis {
    int i0, i1;
    double t;
};

Axis axis(double x, int n) {
    // Wrapping before scaling keeps huge coordinates in range; x - floor(x) is 1 only when a
    // tiny negative x rounds up, and that position is still inside the last texel's span.
    double f = x - std::floor(x);
    if (!(f <= 1)) f = 0;  // NaN or ±∞
    const double s = f * n - 0.5;  // texel centres at integers
    const double s0 = std::floor(s);
    const int i0 = s0 < 0 ? n - 1 : int(s0);  // left of the first centre: between the last and first
    return {i0, i0 + 1 == n ? 0 : i0 + 1, s - s0};
}

// The four texels a lookup weighs: offsets of their first values and bilinear weights.
struct Footprint {
    size_t at[4];
    double w[4];
};

Footprint footprint(const Texture& tex, double u, double v) {
    const Axis x = axis(u, tex.width()), y = axis(v, tex.height());
    const size_t width = size_t(tex.width()), c = size_t(tex.channels());
    // Rows are stored top first and v counts from the bottom.
    const size_t r0 = size_t(tex.height() - 1 - y.i0) * width, r1 = size_t(tex.height() - 1 - y.i1) * width;
    return {{(r0 + size_t(x.i0)) * c, (r0 + size_t(x.i1)) * c, (r1 + size_t(x.i0)) * c, (r1 + size_t(x.i1)) * c},
            {(1 - x.t) * (1 - y.t), x.t * (1 - y.t), (1 - x.t) * y.t, x.t * y.t}};
}

template <typename T, typename Decode>
double weigh(const T* values, const Footprint& f, Decode decode) {
    return f.w[0] * decode(values[f.at[0]]) + f.w[1] * decode(values[f.at[1]]) + f.w[2] * decode(values[f.at[2]]) +
           f.w[3] * decode(values[f.at[3]]);
}

bool has_alpha(int channels) { return channels == 2 || channels == 4; }

// Where channel `pick` (0..3: r, g, b, a) lives in a texel, or -1 for the alpha of a texture
// without one. Grey textures answer r, g and b with their grey.
int source_channel(int channels, int pick) {
    if (pick == 3) return has_alpha(channels) ? channels - 1 : -1;
    return channels >= 3 ? pick : 0;
}

// The filtered linear value of one stored channel (-1: a missing alpha, 1).
double filtered(const Texture& tex, const Footprint& f, int source, ColorSpace colorspace) {
    if (source < 0) return 1;
    if (!tex.is_8bit()) return weigh(tex.floats().data() + source, f, [](float v) { return double(v); });
    const bool alpha = has_alpha(tex.channels()) && source == tex.channels() - 1;  // never sRGB-encoded
    const DecodeTable& table = colorspace == ColorSpace::srgb && !alpha ? kSrgb : kUnit;
    return weigh(tex.bytes().data() + source, f, [&table](uint8_t b) { return table[b]; });
}

void check_shape(int width, int height, int channels, size_t values) {
    if (width < 1 || height < 1 || channels < 1 || channels > 4 ||
        values != size_t(width) * size_t(height) * size_t(channels))
        throw std::invalid_argument("a texture of " + std::to_string(width) + "x" + std::to_string(height) + "x" +
                                    std::to_string(channels) + " cannot hold " + std::to_string(values) + " values");
}

}  // namespace

double srgb_to_linear(uint8_t byte) { return kSrgb[byte]; }

Texture::Texture(int width, int height, int channels, std::vector<uint8_t> bytes, std::vector<float> floats)
    : width_(width), height_(height), channels_(channels), bytes_(std::move(bytes)), floats_(std::move(floats)) {}

Texture Texture::from_bytes(int width, int height, int channels, std::vector<uint8_t> texels) {
    check_shape(width, height, channels, texels.size());
    return Texture(width, height, channels, std::move(texels), {});
}

Texture Texture::from_floats(int width, int height, int channels, std::vector<float> texels) {
    check_shape(width, height, channels, texels.size());
    return Texture(width, height, channels, {}, std::move(texels));
}

Rgb TextureLookup::rgb(double u, double v) const {
    const Footprint f = footprint(*texture, u * uv_scale[0] + uv_offset[0], v * uv_scale[1] + uv_offset[1]);
    const int channels = texture->channels();
    if (channel >= 0 || channels < 3)
        return scale * filtered(*texture, f, source_channel(channels, std::max(channel, 0)), colorspace);
    return scale * Rgb{filtered(*texture, f, 0, colorspace), filtered(*texture, f, 1, colorspace),
                       filtered(*texture, f, 2, colorspace)};
}

double TextureLookup::value(double u, double v) const {
    const Footprint f = footprint(*texture, u * uv_scale[0] + uv_offset[0], v * uv_scale[1] + uv_offset[1]);
    return scale.x * filtered(*texture, f, source_channel(texture->channels(), std::max(channel, 0)), colorspace);
}

}  // namespace glint
