#include "service/denoised_preview.h"

#include "denoise/denoiser.h"
#include "service/errors.h"

namespace glint {

bool DenoisedPreview::begin(uint64_t frame, DenoiseGate& gate, const std::string& job_id,
                            std::shared_ptr<const std::vector<uint8_t>>& kept) {
    std::lock_guard lock(mutex_);
    if (frame_ == frame && png_) {
        kept = png_;
        return false;
    }
    if (denoising_) throw Busy("job " + job_id + "'s denoised preview is being made: try again when it is done");
    if (!gate.try_enter())
        throw Busy("the server is already making as many denoised previews as it may at once (" +
                   std::to_string(gate.limit()) + "): try again later");
    denoising_ = true;
    return true;
}

void DenoisedPreview::finish(DenoiseGate& gate, uint64_t frame, std::shared_ptr<const std::vector<uint8_t>> png) {
    std::lock_guard lock(mutex_);
    denoising_ = false;
    gate.leave();
    if (!png) return;
    png_ = std::move(png);
    frame_ = frame;
}

std::shared_ptr<const std::vector<uint8_t>> DenoisedPreview::png(const JobSnapshot& latest, Encoding encoding,
                                                                 DenoiseGate& gate, const std::string& job_id) {
    if (!latest.halves) return nullptr;
    std::shared_ptr<const std::vector<uint8_t>> kept;
    if (!begin(latest.frame, gate, job_id, kept)) return kept;
    // However the denoiser ends, the place goes back, and a finished frame is kept.
    struct Finish {
        DenoisedPreview& preview;
        DenoiseGate& gate;
        uint64_t frame;
        std::shared_ptr<const std::vector<uint8_t>> png;
        ~Finish() { preview.finish(gate, frame, std::move(png)); }
    } done{*this, gate, latest.frame, nullptr};
    ThreadPool pool(0);  // the request's own threads: the render's pool belongs to the render
    done.png = std::make_shared<const std::vector<uint8_t>>(
        encode_png(denoise(*latest.halves, pool), encoding));
    return done.png;
}

}  // namespace glint
