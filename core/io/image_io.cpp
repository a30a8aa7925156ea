#include "io/image_io.h"

#include <stb_image_write.h>

#include <bit>
#include <cstdio>
#include <cstring>
#include <sstream>

namespace glint {

uint8_t encode_value(double linear, Encoding encoding) {
    const double v = std::clamp(std::isnan(linear) ? 0.0 : linear, 0.0, 1.0);
    const double encoded = encoding == Encoding::gamma22
                               ? std::pow(v, 1 / 2.2)
                               : (v <= 0.0031308 ? 12.92 * v : 1.055 * std::pow(v, 1 / 2.4) - 0.055);
    return static_cast<uint8_t>(encoded * 255 + 0.5);
}

std::vector<uint8_t> encode_png(const Image& image, Encoding encoding) {
    std::vector<uint8_t> pixels(image.rgb.size());
    for (size_t i = 0; i < pixels.size(); ++i) pixels[i] = encode_value(image.rgb[i], encoding);
    std::vector<uint8_t> png;
    auto append = [](void* context, void* data, int size) {
        auto* out = static_cast<std::vector<uint8_t>*>(context);
        out->insert(out->end(), static_cast<uint8_t*>(data), static_cast<uint8_t*>(data) + size);
    };
    if (!stbi_write_png_to_func(append, &png, image.width, image.height, 3, pixels.data(), image.width * 3))
        throw ImageError("PNG encoding failed");
    return png;
}

std::vector<uint8_t> encode_pfm(const Image& image) {
    static_assert(std::endian::native == std::endian::little, "PFM writer assumes a little-endian host");
    const std::string header = "PF\n" + std::to_string(image.width) + " " + std::to_string(image.height) + "\n-1.0\n";
    std::vector<uint8_t> bytes(header.begin(), header.end());
    const size_t row_bytes = size_t(image.width) * 3 * sizeof(float);
    for (int y = image.height - 1; y >= 0; --y) {
        const auto* row = reinterpret_cast<const uint8_t*>(&image.rgb[size_t(y) * image.width * 3]);
        bytes.insert(bytes.end(), row, row + row_bytes);
    }
    return bytes;
}

Image decode_pfm(const std::vector<uint8_t>& bytes) {
    std::string text(bytes.begin(), bytes.begin() + std::min<size_t>(bytes.size(), 64));
    std::istringstream in(text);
    std::string magic;
    int width = 0, height = 0;
    double scale = 0;
    in >> magic >> width >> height >> scale;
    if (!in || magic != "PF" || width <= 0 || height <= 0 || scale >= 0)
        throw ImageError("not a little-endian colour PFM");
    const auto data_start = static_cast<size_t>(in.tellg()) + 1;  // one whitespace byte ends the header
    const size_t row_bytes = size_t(width) * 3 * sizeof(float);
    if (bytes.size() - data_start != row_bytes * size_t(height)) throw ImageError("PFM size does not match its header");
    Image image(width, height);
    for (int y = 0; y < height; ++y)
        std::memcpy(&image.rgb[size_t(height - 1 - y) * width * 3], &bytes[data_start + size_t(y) * row_bytes], row_bytes);
    return image;
}

}  // namespace glint
