// A film as OpenEXR layers (io/exr_file.h): its mean image as R, G, B, then sample_count.Y and
// variance.R/G/B, and with AOVs albedo.R/G/B, N.X/Y/Z and Z (depth); README lists them. Here
// rather than beside the format, which knows images and planes but not the renderer's film.
#pragma once

#include <cstdint>
#include <vector>

#include "base/image.h"
#include "io/exr_file.h"
#include "render/film.h"

namespace glint {

// What a film keeps per pixel besides its mean image: the samples each pixel's mean averages
// (sample_count.Y), the estimated variance of that mean (variance.R/G/B: Film::camera_variance
// plus the splats' Film::splat_variance; 0 where it cannot be estimated yet, a pixel without
// samples in both halves), and the AOVs' means if it has them (albedo.R/G/B, N.X/Y/Z, Z).
std::vector<ExrLayer> film_layers(const Film& film);

// An EXR of a film: `image` (its mean, as R, G, B), film_layers(film), then `extra` (such as the
// denoised preview).
std::vector<uint8_t> encode_film_exr(const Image& image, const Film& film, std::vector<ExrLayer> extra = {});

}  // namespace glint
