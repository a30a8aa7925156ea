// The denoiser's parameters (docs/denoiser.md explains each against the paper it follows), and
// the denoiser run with others than its own. Only bench/denoise_vs_error, which tuned them, and
// the tests that compare settings change them: the service and glint render call denoise()
// (denoiser.h), which has no settings to pass.
#pragma once

#include <vector>

#include "base/image.h"
#include "base/thread_pool.h"
#include "denoise/half_buffers.h"

namespace glint {

struct DenoiserConfig {
    // A candidate filter, a pair of strengths: a colour patch distance of k² times twice the
    // filtered pixel's variance costs the neighbour a weight of e^-1, and so does a feature
    // (AOV) differing by k_f² times its variance (or feature_floor); 0 leaves that test out.
    // Larger k smooths more; each pixel then blends the candidates and its unfiltered value by
    // their estimated errors. Candidates that compare features need the film's AOVs and are
    // left out without them. As in Rousselle et al. 2013: colour alone; colour and features;
    // features alone (the strongest, for flat regions at few samples). A candidate with
    // `regression` fits each pixel's neighbours, weighted so, as a first-order function of the
    // features (regression.h), and needs the AOVs too.
    struct Candidate {
        float colour = 0, feature = 0;
        bool regression = false;
    };
    // Candidates that share a search window and a patch size, so their distances are computed
    // once: each pixel averages over (2·window_radius+1)² neighbours, comparing patches of
    // (2·patch_radius+1)² pixels.
    struct Filter {
        int window_radius = 7;
        int patch_radius = 2;
        std::vector<Candidate> candidates;
    };
    // Two sets of the same five candidates: the last two strong colour weights with the
    // features as regressors rather than as weights.
    // - Wide: a 15×15 window and 5×5 patches remove most of 16 spp's noise in flat regions; a
    //   patch then averages over 75 values, steady enough at a few samples per pixel. Cost
    //   grows with the window's square.
    // - Local: a 7×7 window and 3×3 patches, for edges and objects a few pixels wide, where a
    //   wide window finds few neighbours that are alike and a 5×5 patch straddles the edge. At
    //   16 spp the blend with both lowered the relMSE on five scenes of seven, by up to a sixth,
    //   for a quarter more time (docs/denoiser.md).
    static std::vector<Candidate> standard_candidates() {
        return {{0.45f, 0}, {1.0f, 0}, {0.45f, 0.6f}, {0, 0.6f}, {1.0f, 0, true}};
    }
    std::vector<Filter> filters = {{7, 2, standard_candidates()}, {3, 1, standard_candidates()}};
    // How much of the two pixels' variance the distance takes off (Rousselle et al.'s α):
    // 1 removes the expected squared difference that noise alone makes.
    float variance_cancel = 1.0f;
    // Half-width of the box over which each candidate's per-pixel error estimate is averaged
    // before the blend: one pixel's estimate has one degree of freedom per channel, and 5×5 (2)
    // gives 75 while still following edges and small bright features; 7×7 let one noisy
    // pixel's estimate decide for twice as many neighbours (docs/denoiser.md has the figures).
    int selection_radius = 2;
    // The error estimates are relative: a squared error at a pixel of value v counts divided by
    // v² + this floor (v the least of its candidates), as relMSE weighs it, so that a dark
    // pixel's error is not outweighed by a bright neighbour's noise. 0.01: relMSE's own floor.
    float relative_error_floor = 0.01f;
    // Below this a feature's variance counts as this much: features are nearly noise-free, and
    // a normal or albedo that differs by less than 3% of its range is taken as the same.
    float feature_floor = 1e-3f;
};

// denoise() with `config` for its settings.
Image denoise_with(const HalfBuffers& halves, const DenoiserConfig& config, ThreadPool& pool);

}  // namespace glint
