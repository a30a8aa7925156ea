// PNG and PFM encodings: smallpt's gamma, sRGB, clamping, and PFM's bottom-up row order.
#include <gtest/gtest.h>

#include <stb_image.h>

#include <cstring>

#include "io/image_io.h"

namespace glint {
namespace {

TEST(ImageIo, EncodesValuesAsSmallptAndSrgbDo) {
    EXPECT_EQ(encode_value(0.5, Encoding::gamma22), int(std::pow(0.5, 1 / 2.2) * 255 + 0.5));  // 186
    EXPECT_EQ(encode_value(0.5, Encoding::srgb), 188);
    EXPECT_EQ(encode_value(0.001, Encoding::srgb), int(12.92 * 0.001 * 255 + 0.5));
    EXPECT_EQ(encode_value(-1, Encoding::gamma22), 0);
    EXPECT_EQ(encode_value(7, Encoding::gamma22), 255);
    EXPECT_EQ(encode_value(std::numeric_limits<double>::quiet_NaN(), Encoding::gamma22), 0);
}

Image gradient() {
    Image image(3, 2);
    for (int y = 0; y < 2; ++y)
        for (int x = 0; x < 3; ++x) image.set(x, y, Rgb{0.1 * x, 0.5 * y, 0.25});
    return image;
}

TEST(ImageIo, PfmStoresTheBottomRowFirstAndRoundTrips) {
    const Image image = gradient();
    const std::vector<uint8_t> pfm = encode_pfm(image);
    const std::string header = "PF\n3 2\n-1.0\n";
    ASSERT_EQ(std::string(pfm.begin(), pfm.begin() + long(header.size())), header);
    float first[3];
    std::memcpy(first, &pfm[header.size()], sizeof first);
    EXPECT_EQ(first[1], 0.5f);  // the first stored row is the image's bottom row (y = 1)
    const Image back = decode_pfm(pfm);
    EXPECT_EQ(back.rgb, image.rgb);
}

TEST(ImageIo, PngDecodesToTheEncodedPixels) {
    const Image image = gradient();
    const std::vector<uint8_t> png = encode_png(image, Encoding::gamma22);
    int w, h, channels;
    unsigned char* pixels = stbi_load_from_memory(png.data(), int(png.size()), &w, &h, &channels, 3);
    ASSERT_NE(pixels, nullptr);
    EXPECT_EQ(w, 3);
    EXPECT_EQ(h, 2);
    for (int i = 0; i < 18; ++i) EXPECT_EQ(pixels[i], encode_value(image.rgb[size_t(i)], Encoding::gamma22));
    stbi_image_free(pixels);
}

TEST(ImageIo, RejectsMalformedPfm) {
    const std::string text = "PF\n3 2\n-1.0\nshort";
    EXPECT_THROW(decode_pfm(std::vector<uint8_t>(text.begin(), text.end())), ImageError);
}

}  // namespace
}  // namespace glint
