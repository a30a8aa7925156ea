#include "http/job_images.h"

#include <string>
#include <utility>

#include "base/image.h"
#include "io/exr_file.h"
#include "io/image_io.h"
#include "service/errors.h"

namespace glint {
namespace {

// A jobs list's thumbnails: small enough that a page can list many jobs cheaply.
constexpr int kThumbnailWidth = 128, kThumbnailHeight = 96;

ImageContent encoded(std::vector<uint8_t> bytes) {
    return {std::make_shared<const std::vector<uint8_t>>(std::move(bytes)), {}};
}

ImageContent png(const ImageSource& source) { return {source.snapshot.png, {}}; }

// Made from the frame on request, never in place of image.png.
ImageContent denoised(const ImageSource& source) { return {source.job.denoised_png(source.denoise_gate), {}}; }

ImageContent pfm(const ImageSource& source) {
    const auto& image = source.snapshot.image;
    return image ? encoded(encode_pfm(*image)) : ImageContent{};
}

ImageContent exr(const ImageSource& source) {
    const JobSnapshot& s = source.snapshot;
    if (!s.image) return {};
    std::vector<ExrLayer> layers{exr_layer("", *s.image)};
    if (s.layers) layers.insert(layers.end(), s.layers->begin(), s.layers->end());
    return encoded(encode_exr(s.image->width, s.image->height, layers));
}

// Grey from 0 (black) to the header's X-Glint-Samples-Max.
ImageContent samples(const ImageSource& source) {
    if (!source.job.settings().adaptive.on())
        throw ServiceError(ServiceError::Kind::not_found, "not an adaptive job: every pixel has spp_done samples");
    const JobSnapshot& s = source.snapshot;
    if (!s.samples_png) return {};
    return {s.samples_png, {{"X-Glint-Samples-Max", std::to_string(s.samples_max)}}};
}

ImageContent thumbnail(const ImageSource& source) {
    const auto& image = source.snapshot.image;
    if (!image) return {};
    return encoded(encode_png(downscale(*image, kThumbnailWidth, kThumbnailHeight), source.job.settings().encoding));
}

}  // namespace

const JobImage kPngImage{"image/png", png};
const JobImage kDenoisedImage{"image/png", denoised};
const JobImage kPfmImage{"image/x-portable-floatmap", pfm};
const JobImage kExrImage{"image/x-exr", exr};
const JobImage kSamplesImage{"image/png", samples};
const JobImage kThumbnailImage{"image/png", thumbnail};

}  // namespace glint
