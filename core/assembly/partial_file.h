// Partial renders: the per-pixel sums of samples [first, end) of a job, written by
// `glint render --samples A:B --partial FILE` and combined by `glint merge`.
//
// Format (version 5, little-endian, no padding; versions 2 to 4 are still read, see
// partial_file.cpp):
//   offset  size  field
//   0       8     magic "GLNTPART"
//   8       4     uint32 version = 5
//   12      4     uint32 width
//   16      4     uint32 height
//   20      4     uint32 first sample (inclusive)
//   24      4     uint32 end sample (exclusive)
//   28      4     uint32 PNG encoding (0 gamma 2.2, 1 sRGB)
//   32      4     uint32 sampler version (kSamplerVersion, sampler.h)
//   36      8     uint64 fingerprint of scene and settings (core/assembly/fingerprint.h)
//   44      4     uint32 flags: bit 0 set if the film has AOVs (render/aov.h); no other bits
//   48      8     uint64 light paths traced per pixel, when counted apart from the camera
//                 samples (adaptive sampling with light tracing, Film::light_paths); else 0
//   56      128·W·H per pixel, rows top to bottom: float64 sum r, g, b; float64 sum of the first
//                 half's samples r, g, b; uint64 sample count; uint64 first half's sample count;
//                 uint64 dropped samples; int64 light-tracing splat sums r, g, b and sums of
//                 squares r, g, b (fixed point, see film.h); uint64 dropped splats
//   then, with AOVs only, 112·W·H per pixel in the same order: float64 sums of albedo r, g, b,
//                 normal x, y, z and depth, then the same over the first half's samples
//   end-8   8     uint64 FNV-1a of every byte before it
#pragma once

#include <stdexcept>
#include <vector>

#include "io/image_io.h"
#include "render/film.h"
#include "render/renderer.h"
#include "render/sampler.h"

namespace glint {

struct PartialError : std::runtime_error {
    using std::runtime_error::runtime_error;
};

struct Partial {
    uint64_t fingerprint = 0;
    uint32_t sampler_version = kSamplerVersion;  // that of the glint that rendered it
    uint32_t first_sample = 0, end_sample = 0;
    Encoding encoding = Encoding::gamma22;
    Film film{1, 1};
};

// The film of `render` holding samples [first_sample, first_sample + spp_done) of every pixel;
// `fingerprint` is that of its scene and settings (assembly/fingerprint.h). What `glint render
// --partial` writes and what the service's store checkpoints and keeps when a job ends.
Partial partial_of(const RenderJob& render, uint64_t fingerprint, uint32_t spp_done);

std::vector<uint8_t> encode_partial(const Partial& partial);
uint64_t partial_file_size(int width, int height, bool aovs = false);
Partial decode_partial(const std::vector<uint8_t>& bytes);  // throws PartialError

// Checks that `checkpoint` may continue the job of `fingerprint` and `settings`: same scene and
// settings, sampler version, encoding and first sample (RenderJob::resume then checks its size and
// sample count). Throws std::invalid_argument saying what differs.
void check_continues(const Partial& checkpoint, uint64_t fingerprint, const RenderSettings& settings);

// Combines parts of one job: same fingerprint, sampler version and size, sample ranges that
// neither overlap nor leave gaps (in any order given). Sums are added in order of the ranges. Throws PartialError.
Partial merge_partials(std::vector<Partial> parts);

}  // namespace glint
