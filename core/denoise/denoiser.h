// A denoised preview of a film, after Rousselle, Knaus and Zwicker 2012 and Rousselle, Manzi
// and Zwicker 2013 (non-local means on the film's two independent halves, with its AOVs when it
// has them, and with them the first-order regression of Bitterli et al. 2016 as one more
// candidate; docs/denoiser.md): each half is filtered on its own by a few candidate filters, each
// result's error is estimated per pixel against the other half, and every pixel blends the
// candidates and its unfiltered mean by the inverse squares of their estimated errors. As
// samples grow, the filters' weights shrink with the noise and the unfiltered mean takes over:
// the preview converges to the unbiased image.
#pragma once

#include "base/image.h"
#include "base/thread_pool.h"
#include "denoise/half_buffers.h"
#include "render/film.h"

namespace glint {

// The film's image, denoised with the denoiser's own settings (denoiser_config.h's defaults);
// bit-identical for any pool size. Finite wherever the film is.
Image denoise(const Film& film, ThreadPool& pool);
// The same from what the denoiser reads of a film, kept where the film goes on changing (a
// running job's frame).
Image denoise(const HalfBuffers& halves, ThreadPool& pool);

}  // namespace glint
