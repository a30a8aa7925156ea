#include "base/image.h"

namespace glint {

double rmse(const Image& a, const Image& b) {
    double total = 0;
    for (size_t i = 0; i < a.rgb.size(); ++i) {
        const double d = double(a.rgb[i]) - double(b.rgb[i]);
        total += d * d;
    }
    return std::sqrt(total / double(a.rgb.size()));
}

}  // namespace glint
