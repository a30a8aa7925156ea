// A converged reference of a scene for the benchmarks, rendered once per scene, size and sample
// count and kept in a folder as PFM, with its own error estimate beside it (FILE.estimate), so
// that a reader can take the reference's noise out of an error measured against it: for
// independent unbiased images, E[RMSE²] against the reference is the render's MSE plus the
// reference's.
#pragma once

#include <cstdint>
#include <string>

#include "assembly/scene_loader.h"
#include "base/image.h"

namespace glint {

// `loaded` at its own size, rendered at `spp` with a seed independent of the benchmarks' ladders
// (0x5EED); read back from `folder` if it is there already.
Image reference_image(LoadedScene loaded, const std::string& folder, uint32_t spp, unsigned threads);

}  // namespace glint
