// Texture files decoded from bytes encoded in memory: PNG and OpenEXR give back exactly what was
// written, the same image as PNG and as EXR looks up alike, and every broken file is a
// TextureError that names it.
#include <gtest/gtest.h>

#include <stb_image_write.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <limits>
#include <random>

#include "io/exr_file.h"
#include "io/texture_file.h"
#include "support/image_files.h"

namespace glint {
namespace {

using testing::exr;
using testing::png;

// The texture's values, decoded from an EXR file of one channel per plane.
std::vector<float> exr_floats(const DecodedTexture& decoded) {
    return std::vector<float>(decoded.texture.floats().begin(), decoded.texture.floats().end());
}

// The message of the TextureError that decoding `bytes` throws, or "no error".
std::string error_of(const std::vector<uint8_t>& bytes, const std::string& name, const TextureLimits& limits = {}) {
    try {
        decode_texture(bytes, name, limits);
    } catch (const TextureError& e) {
        return e.what();
    }
    return "no error";
}

// Sets an EXR file's data window (its first dataWindow attribute) to x0, y0, x1, y1.
void set_data_window(std::vector<uint8_t>& file, const std::array<int32_t, 4>& window) {
    const std::string key("dataWindow\0box2i\0", 17);
    const auto at = std::search(file.begin(), file.end(), key.begin(), key.end());
    ASSERT_NE(at, file.end());
    std::memcpy(&*(at + long(key.size()) + 4), window.data(), sizeof window);  // after the size field
}

std::vector<uint8_t> noise(size_t count, unsigned seed) {
    std::mt19937 random(seed);
    std::vector<uint8_t> bytes(count);
    for (uint8_t& b : bytes) b = uint8_t(random() >> 24);
    return bytes;
}

TEST(TextureFile, PngKeepsItsBytesAndChannels) {
    for (int channels = 1; channels <= 4; ++channels) {
        const std::vector<uint8_t> texels = noise(size_t(3 * 2 * channels), unsigned(channels));
        const DecodedTexture decoded = decode_texture(png(3, 2, channels, texels), "a.png");
        const Texture& t = decoded.texture;
        EXPECT_TRUE(t.is_8bit());
        EXPECT_EQ(t.width(), 3);
        EXPECT_EQ(t.height(), 2);
        EXPECT_EQ(t.channels(), channels);
        EXPECT_EQ(std::vector<uint8_t>(t.bytes().begin(), t.bytes().end()), texels);
        EXPECT_EQ(decoded.negative_values, 0u);
    }
}

TEST(TextureFile, PngTopRowIsReadAtTheTopOfTheUvSquare) {
    const DecodedTexture decoded = decode_texture(png(1, 2, 1, {255, 0}), "a.png");
    const TextureLookup l{.texture = &decoded.texture, .colorspace = ColorSpace::linear};
    EXPECT_EQ(l.value(0.5, 0.75), 1);
    EXPECT_EQ(l.value(0.5, 0.25), 0);
}

TEST(TextureFile, ExrKeepsItsFloats) {
    const std::vector<float> r{0.1f, 3.75f, 1e-3f, 12345.678f}, g{0.2f, 0, 1, 2}, b{0.3f, 5, 6, 7};
    const std::vector<float> a{1, 0.5f, 0.25f, 0};
    const DecodedTexture rgba = decode_texture(exr(2, 2, {"R", "G", "B", "A"}, {r, g, b, a}), "a.exr");
    EXPECT_FALSE(rgba.texture.is_8bit());
    EXPECT_EQ(rgba.texture.channels(), 4);
    std::vector<float> interleaved;
    for (size_t i = 0; i < 4; ++i) interleaved.insert(interleaved.end(), {r[i], g[i], b[i], a[i]});
    EXPECT_EQ(exr_floats(rgba), interleaved);

    const DecodedTexture grey = decode_texture(exr(2, 2, {"Y"}, {r}), "y.exr");
    EXPECT_EQ(grey.texture.channels(), 1);
    EXPECT_EQ(exr_floats(grey), r);
    const DecodedTexture grey_alpha = decode_texture(exr(1, 1, {"Y", "A"}, {{0.5f}, {0.25f}}), "ya.exr");
    EXPECT_EQ(exr_floats(grey_alpha), (std::vector<float>{0.5f, 0.25f}));
    const DecodedTexture green = decode_texture(exr(1, 1, {"G"}, {{0.5f}}), "g.exr");  // R and B missing: 0
    EXPECT_EQ(exr_floats(green), (std::vector<float>{0, 0.5f, 0}));
}

TEST(TextureFile, ExrDataWindowAwayFromTheOriginReadsTheSameTexels) {
    const std::vector<float> r{1, 2, 3, 4};
    std::vector<uint8_t> file = exr(2, 2, {"R", "G", "B"}, {r, r, r});
    set_data_window(file, {-5, 0, -4, 1});  // chunks name their rows, not their columns
    const DecodedTexture decoded = decode_texture(file, "moved.exr");
    EXPECT_EQ(exr_floats(decoded), (std::vector<float>{1, 1, 1, 2, 2, 2, 3, 3, 3, 4, 4, 4}));
}

TEST(TextureFile, HdrIsLinearFloat) {
    // Powers of two, which RGBE holds exactly.
    const std::vector<float> texels{1, 0.5f, 0.25f, 2, 4, 0.125f};
    std::vector<uint8_t> file;
    ASSERT_TRUE(stbi_write_hdr_to_func(testing::append_bytes, &file, 2, 1, 3, texels.data()));
    const DecodedTexture decoded = decode_texture(file, "a.hdr");
    EXPECT_FALSE(decoded.texture.is_8bit());
    EXPECT_EQ(decoded.texture.channels(), 3);
    EXPECT_EQ(exr_floats(decoded), texels);
}

TEST(TextureFile, JpegIsEightBit) {
    std::vector<uint8_t> file;
    const std::vector<uint8_t> grey(64, 128);
    ASSERT_TRUE(stbi_write_jpg_to_func(testing::append_bytes, &file, 8, 8, 1, grey.data(), 90));
    const DecodedTexture decoded = decode_texture(file, "a.jpg");
    EXPECT_TRUE(decoded.texture.is_8bit());
    EXPECT_EQ(decoded.texture.channels(), 3);  // stb_image_write's JPEGs are always colour
    for (const uint8_t b : decoded.texture.bytes()) EXPECT_NEAR(b, 128, 2);
}

TEST(TextureFile, SameImageAsPngAndAsLinearExrLooksUpAlike) {
    const std::vector<uint8_t> bytes = noise(3 * 2 * 3, 7);
    std::vector<std::vector<float>> planes(3, std::vector<float>(6));
    for (size_t i = 0; i < 6; ++i)
        for (size_t c = 0; c < 3; ++c) planes[c][i] = float(srgb_to_linear(bytes[i * 3 + c]));
    const DecodedTexture from_png = decode_texture(png(3, 2, 3, bytes), "a.png");
    const DecodedTexture from_exr = decode_texture(exr(3, 2, {"R", "G", "B"}, planes), "a.exr");
    const TextureLookup a{.texture = &from_png.texture, .colorspace = ColorSpace::srgb};
    const TextureLookup b{.texture = &from_exr.texture, .colorspace = ColorSpace::srgb};
    for (const double u : {0.0, 0.1, 0.37, 0.5, 0.93, -1.2})
        for (const double v : {0.0, 0.2, 0.5, 0.81, 3.3}) {
            const Rgb x = a.rgb(u, v), y = b.rgb(u, v);
            for (int c = 0; c < 3; ++c) EXPECT_NEAR(x[c], y[c], 1e-6) << u << " " << v;
        }
}

TEST(TextureFile, NegativeExrValuesBecomeZeroAndAreCounted) {
    const DecodedTexture decoded = decode_texture(exr(2, 1, {"Y"}, {{-0.5f, -1e-3f}}), "neg.exr");
    EXPECT_EQ(exr_floats(decoded), (std::vector<float>{0, 0}));
    EXPECT_EQ(decoded.negative_values, 2u);
    const DecodedTexture rgb = decode_texture(exr(1, 1, {"R", "G", "B"}, {{-1}, {2}, {-3}}), "neg.exr");
    EXPECT_EQ(rgb.negative_values, 2u);
}

// Each broken file's message names it and says what is wrong.
void expect_error(const std::string& message, const std::string& name, const std::string& what) {
    EXPECT_NE(message.find("'" + name + "'"), std::string::npos) << message;
    EXPECT_NE(message.find(what), std::string::npos) << message;
}

TEST(TextureFile, RefusesWhatIsNotAnImage) {
    expect_error(error_of({}, "empty.png"), "empty.png", "is empty");
    expect_error(error_of(noise(256, 1), "noise.png"), "noise.png", "not an image");
    const std::string text = "P3 not really";
    expect_error(error_of(std::vector<uint8_t>(text.begin(), text.end()), "text.ppm"), "text.ppm", "not an image");
}

TEST(TextureFile, RefusesTruncatedFiles) {
    const std::vector<uint8_t> whole_png = png(16, 16, 3, noise(16 * 16 * 3, 3));
    const std::vector<uint8_t> half_png(whole_png.begin(), whole_png.begin() + long(whole_png.size() / 2));
    expect_error(error_of(half_png, "cut.png"), "cut.png", "corrupt or truncated");

    const std::vector<float> plane(16 * 16, 0.5f);
    const std::vector<uint8_t> whole_exr = exr(16, 16, {"R", "G", "B"}, {plane, plane, plane});
    const std::vector<uint8_t> most_exr(whole_exr.begin(), whole_exr.end() - 8);
    expect_error(error_of(most_exr, "cut.exr"), "cut.exr", "corrupt or truncated OpenEXR");
    const std::vector<uint8_t> header_exr(whole_exr.begin(), whole_exr.begin() + 40);
    expect_error(error_of(header_exr, "head.exr"), "head.exr", "truncated or corrupt OpenEXR file (its header)");
}

TEST(TextureFile, RefusesNanAndInfinity) {
    for (const float bad : {std::numeric_limits<float>::quiet_NaN(), std::numeric_limits<float>::infinity()})
        expect_error(error_of(exr(2, 1, {"Y"}, {{0.5f, bad}}), "bad.exr"), "bad.exr", "holds a NaN or infinite texel");
}

TEST(TextureFile, RefusesImagesAboveTheTexelLimit) {
    const TextureLimits limits{.max_texels_per_file = 15};
    expect_error(error_of(png(4, 4, 1, std::vector<uint8_t>(16)), "big.png", limits), "big.png",
                 "is 4x4 texels, more than the 15 a texture may have");
    expect_error(error_of(exr(4, 4, {"Y"}, {std::vector<float>(16)}), "big.exr", limits), "big.exr",
                 "is 4x4 texels, more than the 15");
    EXPECT_EQ(error_of(png(4, 4, 1, std::vector<uint8_t>(16)), "fits.png", {.max_texels_per_file = 16}), "no error");
}

TEST(TextureFile, ExrDeclaringAHugeImageIsRefusedFromItsHeader) {
    std::vector<uint8_t> file = exr(2, 2, {"Y"}, {std::vector<float>(4)});
    set_data_window(file, {-(1 << 30), 0, 1 << 30, 1 << 30});
    expect_error(error_of(file, "huge.exr"), "huge.exr", "texels, more than the");
    // Within the texel limit but one texel wide: OpenEXR's tables of one entry per row would
    // take more than the limit's worth of memory.
    set_data_window(file, {0, 0, 0, (1 << 26) - 1});
    expect_error(error_of(file, "tall.exr"), "tall.exr", "need more memory to read");
}

}  // namespace
}  // namespace glint
