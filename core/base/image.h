// A linear RGB float image, top row first.
#pragma once

#include <vector>

#include "base/math.h"

namespace glint {

// How linear radiance becomes an 8-bit value. gamma22 is smallpt's pure 1/2.2 power law.
enum class Encoding { gamma22, srgb };

struct Image {
    int width = 0, height = 0;
    std::vector<float> rgb;  // 3 floats per pixel, rows top to bottom

    Image() = default;
    Image(int w, int h) : width(w), height(h), rgb(size_t(w) * h * 3, 0.0f) {}
    Rgb at(int x, int y) const {
        const float* p = &rgb[(size_t(y) * width + x) * 3];
        return {p[0], p[1], p[2]};
    }
    void set(int x, int y, const Rgb& c) {
        float* p = &rgb[(size_t(y) * width + x) * 3];
        p[0] = float(c.x), p[1] = float(c.y), p[2] = float(c.z);
    }
};

// The image made smaller by a whole factor, the least that fits it in max_width × max_height,
// each pixel the mean of its block (a thumbnail); an image that fits already is returned as is.
Image downscale(const Image& image, int max_width, int max_height);

// Root-mean-square difference over all pixels and channels; images must match in size.
double rmse(const Image& a, const Image& b);

}  // namespace glint
