// A render's film saved at pass ends, at most every `interval` seconds, so that a render that
// is stopped continues from the last one with the samples and sums an uninterrupted render
// would have. Between passes the film holds whole passes. Where the film goes is the caller's:
// the job store for a served job, a file for `glint render --checkpoint`.
#pragma once

#include <chrono>
#include <cstdint>
#include <functional>

#include "assembly/partial_file.h"
#include "render/renderer.h"

namespace glint {

class Checkpointer {
public:
    // `fingerprint` is the render's scene and settings' (io/fingerprint.h), written into the film.
    Checkpointer(double interval, uint64_t fingerprint) : interval_(interval), fingerprint_(fingerprint) {}

    // Called after a pass: gives `save` the film of `render`'s whole passes if `interval` has
    // passed since the last save ended (or `now`); returns whether it did.
    bool after_pass(const RenderJob& render, const std::function<void(const Partial&)>& save, bool now = false);
    // Continues `render` from `saved`. Throws std::invalid_argument saying what differs if it is
    // not this render's film.
    void resume(RenderJob& render, const Partial& saved) const;
    uint64_t fingerprint() const { return fingerprint_; }

private:
    double interval_;
    uint64_t fingerprint_;
    std::chrono::steady_clock::time_point last_ = std::chrono::steady_clock::now();
};

}  // namespace glint
