// The mean over a (2r+1)² box of a single-channel image, the box clipped at the image's border.
#pragma once

#include <vector>

namespace glint {

// `values` holds width × height floats, rows top first; returns the box means.
std::vector<float> box_filter(const std::vector<float>& values, int width, int height, int radius);

}  // namespace glint
