// Deterministic random streams keyed by (seed, pixel, sample index).
// Every sample owns its own stream, so an image does not depend on thread count, tile order or
// how a job's samples are split into passes or over machines.
#pragma once

#include <cstdint>

namespace glint {

// SplitMix64's finaliser (Steele, Lea, Flood 2014): a bijective 64-bit mixer with full avalanche.
constexpr uint64_t mix64(uint64_t z) {
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    return z ^ (z >> 31);
}

class Rng {
public:
    Rng(uint64_t seed, uint64_t pixel, uint64_t sample)
        : state_(mix64(mix64(mix64(seed) ^ pixel) ^ sample)) {}

    uint64_t next_u64() {
        state_ += 0x9E3779B97F4A7C15ull;  // Weyl sequence: period 2^64 per stream
        return mix64(state_);
    }
    // Uniform in [0, 1): the top 53 bits, so every value is exactly representable.
    double uniform() { return static_cast<double>(next_u64() >> 11) * 0x1.0p-53; }

private:
    uint64_t state_;
};

}  // namespace glint
