// What each of a job's image routes (README: GET /jobs/{id}/image.png, ...) makes of the job.
// Finding the job, taking its snapshot and answering 409 while there is nothing to send are
// the same for all of them: HttpApi::image.
#pragma once

#include <cstdint>
#include <memory>
#include <vector>

#include <httplib.h>

#include "service/job.h"

namespace glint {

// What an image is made from.
struct ImageSource {
    const Job& job;
    const JobSnapshot& snapshot;  // the job's latest
    DenoiseGate& denoise_gate;    // the service's bound on denoised previews made at once
};

// Null bytes while no pass has finished (409); else the bytes and the headers sent beside them.
struct ImageContent {
    std::shared_ptr<const std::vector<uint8_t>> bytes;
    httplib::Headers headers;
};

// One image route's own part. `make` throws ServiceError for the answers other than 409: 404
// for the samples of a job without adaptive sampling, 429 while denoising is busy.
struct JobImage {
    const char* content_type;
    ImageContent (*make)(const ImageSource& source);
};

// The latest frame as 8-bit PNG, its denoised preview (docs/denoiser.md), linear PFM and EXR
// (with the film's layers), an adaptive job's samples per pixel, and a thumbnail for lists.
extern const JobImage kPngImage, kDenoisedImage, kPfmImage, kExrImage, kSamplesImage, kThumbnailImage;

}  // namespace glint
