// Texture lookups against values worked out by hand: the sRGB table, bilinear weights between
// texel centres, wrapping, the bottom-up v axis, channel picking, and decoding before filtering.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <stdexcept>

#include "scene/texture.h"

namespace glint {
namespace {

TextureLookup use(const Texture& texture, ColorSpace colorspace = ColorSpace::linear, int channel = -1) {
    return TextureLookup{.texture = &texture, .colorspace = colorspace, .channel = channel};
}

// 2×2, one float channel: rows top first, so the bottom row (v < 0.5) is 3, 4.
Texture two_by_two() { return Texture::from_floats(2, 2, 1, {1, 2, 3, 4}); }
// 3×2: top row 0, 10, 20; bottom row 30, 40, 50.
Texture three_by_two() { return Texture::from_floats(3, 2, 1, {0, 10, 20, 30, 40, 50}); }

TEST(Texture, SrgbTableIsTheExactEotf) {
    for (const int b : {0, 10, 11, 128, 255}) {
        const double c = b / 255.0;
        const double expected = c <= 0.04045 ? c / 12.92 : std::pow((c + 0.055) / 1.055, 2.4);
        EXPECT_EQ(srgb_to_linear(uint8_t(b)), expected) << b;
    }
    EXPECT_EQ(srgb_to_linear(10), 10 / 255.0 / 12.92);  // 10 is below the curve's knee, 11 above
    EXPECT_EQ(srgb_to_linear(11), std::pow((11 / 255.0 + 0.055) / 1.055, 2.4));
    EXPECT_EQ(srgb_to_linear(0), 0.0);
    EXPECT_EQ(srgb_to_linear(255), 1.0);
}

TEST(Texture, EightBitTexelsDecodeAsTheLookupSays) {
    const Texture t = Texture::from_bytes(1, 1, 1, {128});
    EXPECT_EQ(use(t, ColorSpace::srgb).value(0.5, 0.5), srgb_to_linear(128));
    EXPECT_EQ(use(t, ColorSpace::linear).value(0.5, 0.5), 128 / 255.0);
}

TEST(Texture, TexelCentresReturnTheirTexel) {
    const Texture t = two_by_two();
    const TextureLookup l = use(t);
    EXPECT_EQ(l.value(0.25, 0.25), 3);  // column 0, bottom row
    EXPECT_EQ(l.value(0.75, 0.25), 4);
    EXPECT_EQ(l.value(0.25, 0.75), 1);  // column 0, top row
    EXPECT_EQ(l.value(0.75, 0.75), 2);
    const Texture wide = three_by_two();
    const TextureLookup w = use(wide);
    for (int i = 0; i < 3; ++i) {  // thirds are inexact in binary: within rounding
        EXPECT_NEAR(w.value((i + 0.5) / 3, 0.25), 30 + 10 * i, 1e-12);
        EXPECT_NEAR(w.value((i + 0.5) / 3, 0.75), 10 * i, 1e-12);
    }
}

TEST(Texture, FiltersBilinearlyBetweenTexelCentres) {
    const Texture t = two_by_two();
    // u = 0.375: a quarter of the way from column 0's centre to column 1's; v = 0.625: three
    // quarters of the way from the bottom row's centre to the top row's.
    EXPECT_EQ(use(t).value(0.375, 0.625), 0.75 * 0.25 * 3 + 0.25 * 0.25 * 4 + 0.75 * 0.75 * 1 + 0.25 * 0.75 * 2);
    EXPECT_EQ(use(t).value(0.375, 0.625), 1.75);
    EXPECT_EQ(use(t).value(0.5, 0.5), 2.5);  // the middle: the four texels' mean
    const Texture wide = three_by_two();
    // u = 0.7: 1.6 texel centres in, 0.6 of the way from column 1 to 2; v = 0.5: halfway up.
    EXPECT_NEAR(use(wide).value(0.7, 0.5), 0.4 * 0.5 * 40 + 0.6 * 0.5 * 50 + 0.4 * 0.5 * 10 + 0.6 * 0.5 * 20, 1e-12);
    EXPECT_NEAR(use(wide).value(0.7, 0.5), 31, 1e-12);
}

TEST(Texture, FiltersAcrossTheWrappedEdges) {
    const Texture wide = three_by_two();
    // u = 0.1 is left of column 0's centre: 0.8 of column 0 and 0.2 of column 2 (bottom row).
    EXPECT_NEAR(use(wide).value(0.1, 0.25), 0.8 * 30 + 0.2 * 50, 1e-12);
    const Texture t = two_by_two();
    // v = 0.95 is above the top row's centre: 0.6 of the top row and 0.4 of the bottom (column 0).
    EXPECT_NEAR(use(t).value(0.25, 0.95), 0.6 * 1 + 0.4 * 3, 1e-12);
    EXPECT_EQ(use(t).value(0, 0), 2.5);  // the corner: all four texels equally
}

TEST(Texture, WrapsCoordinatesOfAnySize) {
    const Texture wide = three_by_two();
    const TextureLookup l = use(wide);
    EXPECT_EQ(l.value(1.25, 0.3), l.value(0.25, 0.3));
    EXPECT_EQ(l.value(-0.75, 0.3), l.value(0.25, 0.3));
    EXPECT_EQ(l.value(1e9 + 0.25, 0.3), l.value(0.25, 0.3));
    EXPECT_EQ(l.value(0.3, 2.25), l.value(0.3, 0.25));
    EXPECT_EQ(l.value(0.3, -3.75), l.value(0.3, 0.25));
    const double nan = std::numeric_limits<double>::quiet_NaN(), inf = std::numeric_limits<double>::infinity();
    for (const double x : {nan, inf, -inf, 1e300, -1e300, 1e-300, -1e-300, -1e-20})
        for (const double y : {0.3, x}) {
            EXPECT_TRUE(std::isfinite(l.value(x, y))) << x;
            EXPECT_TRUE(is_finite(l.rgb(y, x))) << x;
        }
}

TEST(Texture, VCountsFromTheBottomRow) {
    const Texture t = Texture::from_floats(1, 2, 1, {1, 0});  // the top row (first in memory) is 1
    EXPECT_EQ(use(t).value(0.5, 0.25), 0);
    EXPECT_EQ(use(t).value(0.5, 0.75), 1);
    const Texture bytes = Texture::from_bytes(1, 2, 1, {255, 0});
    EXPECT_EQ(use(bytes).value(0.5, 0.25), 0);
    EXPECT_EQ(use(bytes).value(0.5, 0.75), 1);
}

TEST(Texture, PicksChannelsOfRgba) {
    const Texture t = Texture::from_bytes(1, 1, 4, {10, 20, 30, 40});
    EXPECT_EQ(use(t).rgb(0.5, 0.5), (Rgb{10 / 255.0, 20 / 255.0, 30 / 255.0}));
    for (int c = 0; c < 4; ++c) {
        EXPECT_EQ(use(t, ColorSpace::linear, c).value(0.5, 0.5), (10 + 10 * c) / 255.0);
        EXPECT_EQ(use(t, ColorSpace::linear, c).rgb(0.5, 0.5), Rgb((10 + 10 * c) / 255.0));  // grey
    }
    EXPECT_EQ(use(t, ColorSpace::srgb).rgb(0.5, 0.5),
              (Rgb{srgb_to_linear(10), srgb_to_linear(20), srgb_to_linear(30)}));
    EXPECT_EQ(use(t, ColorSpace::srgb, 1).value(0.5, 0.5), srgb_to_linear(20));
    EXPECT_EQ(use(t, ColorSpace::srgb, 3).value(0.5, 0.5), 40 / 255.0);  // alpha is never sRGB
}

TEST(Texture, FillsInChannelsAGreyOrOpaqueTextureLacks) {
    const Texture rgb = Texture::from_bytes(1, 1, 3, {10, 20, 30});
    EXPECT_EQ(use(rgb, ColorSpace::srgb, 3).value(0.5, 0.5), 1);  // no alpha: opaque
    const Texture grey = Texture::from_bytes(1, 1, 1, {100});
    EXPECT_EQ(use(grey, ColorSpace::srgb).rgb(0.5, 0.5), Rgb(srgb_to_linear(100)));
    for (int c = 0; c < 3; ++c) EXPECT_EQ(use(grey, ColorSpace::srgb, c).value(0.5, 0.5), srgb_to_linear(100));
    EXPECT_EQ(use(grey, ColorSpace::srgb, 3).value(0.5, 0.5), 1);
    const Texture grey_alpha = Texture::from_bytes(1, 1, 2, {100, 200});
    EXPECT_EQ(use(grey_alpha, ColorSpace::srgb).rgb(0.5, 0.5), Rgb(srgb_to_linear(100)));
    EXPECT_EQ(use(grey_alpha, ColorSpace::srgb, 1).value(0.5, 0.5), srgb_to_linear(100));
    EXPECT_EQ(use(grey_alpha, ColorSpace::srgb, 2).value(0.5, 0.5), srgb_to_linear(100));
    EXPECT_EQ(use(grey_alpha, ColorSpace::srgb, 3).value(0.5, 0.5), 200 / 255.0);
}

TEST(Texture, ValueOfTheColourIsTheFirstChannel) {
    const Texture t = Texture::from_floats(1, 1, 3, {0.25f, 0.5f, 0.75f});
    EXPECT_EQ(use(t).value(0.5, 0.5), 0.25);
    TextureLookup scaled = use(t);
    scaled.scale = Rgb{2, 3, 4};
    EXPECT_EQ(scaled.value(0.5, 0.5), 0.5);  // scale.x
}

TEST(Texture, InterpolatesLinearValuesNotEncodedBytes) {
    const Texture t = Texture::from_bytes(2, 1, 1, {0, 255});
    const double middle = use(t, ColorSpace::srgb).value(0.5, 0.5);
    EXPECT_EQ(middle, 0.5);  // (0 + 1) / 2, where decoding byte 127.5 would give about 0.21
    EXPECT_LT(srgb_to_linear(128), 0.22);
}

TEST(Texture, ScalesTheResultAndTransformsCoordinates) {
    const Texture t = Texture::from_floats(3, 2, 3, {0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 13, 14, 15, 16, 17});
    TextureLookup l = use(t);
    l.scale = Rgb{2, 3, 4};
    l.uv_scale[0] = 2;
    l.uv_scale[1] = 0.5;
    l.uv_offset[0] = 0.25;
    l.uv_offset[1] = 0.1;
    const TextureLookup plain = use(t);
    for (const double u : {0.0, 0.3, 0.71, -2.2})
        for (const double v : {0.0, 0.45, 1.9}) {
            EXPECT_EQ(l.rgb(u, v), (plain.rgb(u * 2 + 0.25, v * 0.5 + 0.1) * Rgb{2, 3, 4}));
            EXPECT_EQ(l.value(u, v), plain.value(u * 2 + 0.25, v * 0.5 + 0.1) * 2);
        }
}

TEST(Texture, FloatTexelsAreLinearWhateverTheLookupSays) {
    const Texture t = Texture::from_floats(1, 1, 1, {7.5f});
    EXPECT_EQ(use(t, ColorSpace::srgb).value(0.5, 0.5), 7.5);
    EXPECT_EQ(use(t, ColorSpace::linear).rgb(0.5, 0.5), Rgb(7.5));
}

TEST(Texture, KnowsItsStorage) {
    const Texture bytes = Texture::from_bytes(2, 2, 3, std::vector<uint8_t>(12));
    EXPECT_TRUE(bytes.is_8bit());
    EXPECT_EQ(bytes.memory_bytes(), 12u);
    EXPECT_EQ(bytes.width(), 2);
    EXPECT_EQ(bytes.channels(), 3);
    const Texture floats = Texture::from_floats(2, 2, 3, std::vector<float>(12));
    EXPECT_FALSE(floats.is_8bit());
    EXPECT_EQ(floats.memory_bytes(), 48u);
}

TEST(Texture, RefusesTexelsThatDoNotFitItsShape) {
    EXPECT_THROW(Texture::from_bytes(2, 2, 3, std::vector<uint8_t>(11)), std::invalid_argument);
    EXPECT_THROW(Texture::from_bytes(1, 1, 5, std::vector<uint8_t>(5)), std::invalid_argument);
    EXPECT_THROW(Texture::from_bytes(0, 1, 1, {}), std::invalid_argument);
    EXPECT_THROW(Texture::from_floats(1, -1, 1, {}), std::invalid_argument);
}

}  // namespace
}  // namespace glint
