// The denoiser's parameters (docs/denoiser.md explains each against the paper it follows).
#pragma once

#include <vector>

namespace glint {

struct DenoiserConfig {
    // Half-width of the search window: each pixel averages over (2r+1)² neighbours. 7 (15×15)
    // removes most of 16 spp's noise on the scenes in scenes/ and keeps a 1024×768 image in
    // seconds; the cost grows with its square.
    int window_radius = 7;
    // Half-width of the patches compared: 5×5 patches (2) make the distance between two pixels
    // an average over 75 values, steady enough at a few samples per pixel, and still follow
    // edges a few pixels wide.
    int patch_radius = 2;
    // The candidate filters' strengths k: a patch distance of k² times the two pixels' variance
    // costs the neighbour a weight of e^-1. Larger k smooths more; each pixel then takes the
    // candidate (or its unfiltered value) whose estimated error is least.
    std::vector<float> strengths = {0.45f, 1.0f};
    // How much of the two pixels' variance the distance takes off (Rousselle et al.'s α):
    // 1 removes the expected squared difference that noise alone makes.
    float variance_cancel = 1.0f;
    // Half-width of the box over which each candidate's per-pixel error estimate is averaged
    // before a pixel picks one: one pixel's estimate has one degree of freedom per channel.
    int selection_radius = 3;
};

}  // namespace glint
