#include "base/image.h"

#include <algorithm>

namespace glint {

double rmse(const Image& a, const Image& b) {
    double total = 0;
    for (size_t i = 0; i < a.rgb.size(); ++i) {
        const double d = double(a.rgb[i]) - double(b.rgb[i]);
        total += d * d;
    }
    return std::sqrt(total / double(a.rgb.size()));
}

Image downscale(const Image& image, int max_width, int max_height) {
    const int k = std::max({1, (image.width + max_width - 1) / max_width, (image.height + max_height - 1) / max_height});
    Image out((image.width + k - 1) / k, (image.height + k - 1) / k);
    for (int y = 0; y < out.height; ++y)
        for (int x = 0; x < out.width; ++x) {
            Rgb sum{0};
            int n = 0;
            for (int j = y * k; j < std::min(image.height, (y + 1) * k); ++j)
                for (int i = x * k; i < std::min(image.width, (x + 1) * k); ++i, ++n) sum += image.at(i, j);
            out.set(x, y, sum / double(n));
        }
    return out;
}

}  // namespace glint
