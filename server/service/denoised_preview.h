// A job's latest frame denoised (denoise/denoiser.h), as PNG: made on the first request for a
// frame, inside the service's DenoiseGate, and kept until the next frame. A request never waits
// for one: while it is being made, or when the gate is full, it is refused as busy.
#pragma once

#include <cstdint>
#include <memory>
#include <mutex>
#include <string>
#include <vector>

#include "render/settings.h"
#include "service/denoise_gate.h"
#include "service/job_status.h"

namespace glint {

class DenoisedPreview {
public:
    // Null while `latest` has no film data (before the first pass). Throws Busy
    // (service/errors.h) when its frame is not made yet and the gate is full or the frame is
    // being made for another request. `job_id` names the job in that message.
    std::shared_ptr<const std::vector<uint8_t>> png(const JobSnapshot& latest, Encoding encoding, DenoiseGate& gate,
                                                    const std::string& job_id);

private:
    // Takes the right to make `frame`'s preview; false with it kept: the caller returns `kept`.
    bool begin(uint64_t frame, DenoiseGate& gate, const std::string& job_id,
               std::shared_ptr<const std::vector<uint8_t>>& kept);
    void finish(DenoiseGate& gate, uint64_t frame, std::shared_ptr<const std::vector<uint8_t>> png);

    std::mutex mutex_;  // guards the three below, never held while denoising
    bool denoising_ = false;  // a request is making this job's preview
    uint64_t frame_ = 0;
    std::shared_ptr<const std::vector<uint8_t>> png_;
};

}  // namespace glint
