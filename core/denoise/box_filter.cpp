#include "denoise/box_filter.h"

#include <algorithm>

namespace glint {
namespace {

// The sums over [i - r, i + r] ∩ [0, n) of a line of n values `stride` apart, and the counts.
void box_line(const float* in, float* out, int n, size_t stride, int r) {
    double sum = 0;
    for (int i = 0; i < std::min(r, n); ++i) sum += in[size_t(i) * stride];
    for (int i = 0; i < n; ++i) {
        if (i + r < n) sum += in[size_t(i + r) * stride];
        if (i - r - 1 >= 0) sum -= in[size_t(i - r - 1) * stride];
        const int count = std::min(n - 1, i + r) - std::max(0, i - r) + 1;
        out[size_t(i) * stride] = float(sum / count);
    }
}

}  // namespace

std::vector<float> box_filter(const std::vector<float>& values, int width, int height, int radius) {
    std::vector<float> rows(values.size()), out(values.size());
    for (int y = 0; y < height; ++y)
        box_line(&values[size_t(y) * width], &rows[size_t(y) * width], width, 1, radius);
    for (int x = 0; x < width; ++x) box_line(&rows[x], &out[x], height, size_t(width), radius);
    return out;
}

}  // namespace glint
