// A render's film as a partial file (io/partial_file.h): what `glint render --partial` writes
// and what the store checkpoints and keeps when a job ends, built in this one place.
#pragma once

#include <cstdint>

#include "io/partial_file.h"
#include "render/renderer.h"

namespace glint {

// The film of `render` holding samples [first_sample, first_sample + spp_done) of every pixel;
// `fingerprint` is that of its scene and settings (io/fingerprint.h).
Partial partial_of(const RenderJob& render, uint64_t fingerprint, uint32_t spp_done);

}  // namespace glint
