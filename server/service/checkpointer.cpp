#include "service/checkpointer.h"

namespace glint {

bool Checkpointer::after_pass(const RenderJob& render, const std::function<void(const Partial&)>& save, bool now) {
    using Clock = std::chrono::steady_clock;
    if (!now && Clock::now() - last_ < std::chrono::duration<double>(interval_)) return false;
    save(partial_of(render, fingerprint_, render.progress().spp_done));
    last_ = Clock::now();
    return true;
}

void Checkpointer::resume(RenderJob& render, const Partial& saved) const {
    check_continues(saved, fingerprint_, render.settings());
    render.resume(saved.film, saved.end_sample - saved.first_sample);
}

}  // namespace glint
