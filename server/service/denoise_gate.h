// How many denoised previews the service makes at once (ServiceConfig::max_denoising). A preview
// is made on the thread of the HTTP request that asks for it, with a pool of one thread per
// core, and a large one takes a while (about a minute of CPU at 1024×768: docs/denoiser.md).
// Without a bound, a few such requests would hold every core and every connection thread; with
// it, a request beyond the bound is refused as busy at once instead of waiting.
#pragma once

#include <mutex>

namespace glint {

class DenoiseGate {
public:
    explicit DenoiseGate(unsigned limit) : limit_(limit) {}
    DenoiseGate(const DenoiseGate&) = delete;
    DenoiseGate& operator=(const DenoiseGate&) = delete;

    // Takes one of the places and returns true, or returns false when all `limit` are taken.
    bool try_enter() {
        std::lock_guard lock(mutex_);
        if (inside_ >= limit_) return false;
        ++inside_;
        return true;
    }
    void leave() {
        std::lock_guard lock(mutex_);
        --inside_;
    }
    unsigned limit() const { return limit_; }

private:
    std::mutex mutex_;
    unsigned inside_ = 0;
    const unsigned limit_;
};

}  // namespace glint
