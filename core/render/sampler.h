// Where a camera sample's stratified numbers come from: each stratified dimension (the film
// position, the first diffuse vertex's light sample and its bounce, the direct view's film
// positions) is a two-dimensional scrambled Sobol' sequence of its own, read at a shuffled index.
//
// Why shuffled. Sobol's first two dimensions form a (0,2)-sequence, the best-stratified 2D points
// there are, but only two of them exist; the higher Sobol' dimensions are stratified jointly only
// with some partners and not uniformly well. The usual answer is padding (Kollig and Keller
// 2002; pbrt-v4's PaddedSobolSampler): every 2D dimension reuses the same good 2D sequence, each
// with its own scramble. Scrambling the points is not enough on its own: a nested (Owen)
// scramble is a fixed one-to-one map of the value it scrambles, so two dimensions that read the
// same index of the same sequence are exact functions of each other within a pixel (the light
// sample a function of the film position), and wherever the integrand depends on both at once
// (an edge lit by an area light, a shadow's edge) the estimate converges, within one render, to
// a value that depends on the seed: unbiased over seeds, never consistent, and invisible to the
// error estimate. What decouples them is a different order per dimension: dimension d reads
// point shuffle_d(i) for sample i, a permutation keyed by (seed, pixel, dimension).
//
// Which permutation. pbrt-v4 permutes [0, spp) at random, which needs the sample count up front.
// glint's jobs stop at a target error or a time limit and are split into sample ranges over
// machines, so the order must not depend on the count. A nested scramble of the index itself
// (Burley 2020, "Practical Hash-based Owen Scrambling": each bit of the index flipped by a
// hash of the bits above it) maps every aligned block of 2^m indices onto an aligned block of
// 2^m indices. The first 2^m samples of a dimension are therefore 2^m consecutive points of the
// Sobol' sequence, starting at a multiple of 2^m: a (0,m,2)-net, as well stratified as the
// sequence's own prefix, for every m at once. Two dimensions' orders are independent nested
// scrambles, so their pairing is one too: within a pixel each dimension is stratified on its own
// and independent of the others (tests/test_sampler.cpp checks both, with χ² tests over many
// pixels and sample counts).
//
// Two replicates. The film estimates each pixel's error from the difference between two halves
// of its samples (film.h), which is unbiased only if the halves are independent. A variance
// taken over the samples or rounds of one stratified sequence counts its strata as noise and
// overstates the error wherever stratification pays (up to 2.1× on a checker lit by an area
// light, tests/test_convergence.cpp).
// So every sequence above exists twice, keyed apart: the even rounds of a pixel read one
// replicate, the odd rounds the other, each in its own order as if the other did not exist; the
// image is the two replicates' mean. This is randomized quasi-Monte Carlo's usual error estimate
// (Owen 1997; L'Ecuyer and Lemieux 2002), with the smallest number of replicates that has one.
// Its price is the stratification one net of N points has over two of N/2: on the checker, at 4096
// spp, none measurable (its edges keep the MSE near 1/N); at 64 spp, 4-11% more RMSE.
//
// Everything is a function of (seed, pixel, sample index), so an image is still bit-identical
// for any thread count, split or resume.
#pragma once

#include <cstdint>

#include "base/rng.h"
#include "base/sobol.h"

namespace glint {

// The keys that set a render's random numbers apart, all in one place so that no two streams
// coincide. Each value is part of every image: changing one changes the pixels (and calls for a
// new kSamplerVersion).
namespace sample_keys {
// XORed into the seed before the pixel's stratified dimensions are keyed from it, so that their
// scrambles are not functions of the random streams' keys, which start from mix64(seed).
inline constexpr uint64_t kStratified = 0xF11Du;
// XORed into a dimension's key for the permutation of its sample order, keying the order apart
// from the scramble of its points.
inline constexpr uint64_t kShuffle = 0x5EEDu;
// A pixel's stratified sequences: a replicate's sequence for subpixel s is stream
// replicate << kReplicateShift | s; the one shared by all its subpixels is
// replicate << kReplicateShift | kWholePixel (subpixels number fewer than kWholePixel).
inline constexpr uint32_t kReplicateShift = 8;
inline constexpr uint32_t kWholePixel = 0xFF;
// Set in the sample index of a camera sample's light path (light_tracer.h): an index is 32 bits,
// so its stream is never a camera sample's.
inline constexpr uint64_t kLightPath = uint64_t(1) << 63;
// Set in the index of a path guide's training path (path_guide.h), apart from both.
inline constexpr uint64_t kGuideTraining = uint64_t(1) << 62;
// The direct view's probes (direct_view.h) take seed 0, not the job's: which pixels split must
// not depend on the seed, so that the parts of a job rendered apart decide alike.
inline constexpr uint64_t kProbeSeed = 0;
}  // namespace sample_keys

// The random stream of sample `index` of pixel `pixel`: everything a camera path does not take
// from the stratified dimensions, and all of it with the independent sampler.
inline Rng camera_stream(uint64_t seed, uint64_t pixel, uint32_t index) { return Rng(seed, pixel, index); }
// The stream of that sample's light path.
inline Rng light_path_stream(uint64_t seed, uint64_t pixel, uint32_t index) {
    return Rng(seed, pixel, uint64_t(index) | sample_keys::kLightPath);
}
// The stream of training path `index` of pixel `pixel` for the path guide.
inline Rng guide_training_stream(uint64_t seed, uint64_t pixel, uint32_t index) {
    return Rng(seed, pixel, uint64_t(index) | sample_keys::kGuideTraining);
}
// The stream of the direct view's probe number `probe` on the job's probe grid.
inline Rng probe_stream(uint64_t probe) { return Rng(sample_keys::kProbeSeed, probe, 0); }

// sobol: the shuffled, scrambled Sobol' dimensions above. independent: every number
// from the sample's own random stream, as smallpt draws them (for comparing with smallpt's
// estimator, and the reference the tests measure the stratified sampler against).
enum class Sampler { sobol, independent };

// Changes whenever the points a sampler gives a (seed, pixel, sample) change, so that a film
// rendered with other points is never merged with or resumed by this version's: partial files
// record it (partial_file.h).
inline constexpr uint32_t kSamplerVersion = 3;

// The numbers a camera path's first diffuse vertex takes from the sampler instead of its random
// stream: the light sample there and the direction of the bounce from it.
struct FirstVertexSamples {
    double light[2];
    double bounce[2];
};

// A camera sample's stratified numbers: where in its subpixel the ray goes, and its first
// diffuse vertex's.
struct StratifiedSample {
    double film[2];
    FirstVertexSamples first;
};

// Which of a pixel's two replicates sample `index` draws from: the even rounds the first, the
// odd rounds the second (`round`: samples_per_round of the filter).
inline bool first_replicate(uint32_t index, uint32_t round) { return (index / round) % 2 == 0; }

class PixelSampler {
public:
    // `round`: the samples that cover the pixel's subpixels once (samples_per_round of the filter);
    // sample i goes to subpixel i mod round.
    PixelSampler(uint64_t seed, uint64_t pixel, uint32_t round)
        : key_(mix64(mix64(seed ^ sample_keys::kStratified) ^ pixel)), round_(round) {}

    // The film position is stratified over its subpixel's samples (a sequence per subpixel); the
    // first vertex's numbers over all the pixel's samples (the light seen from one subpixel's
    // first vertex hardly differs from another's). Each of the two replicates has sequences of
    // its own, and its rounds read them as if the other's did not exist.
    StratifiedSample sample(uint32_t index) const {
        const Position at = position(index);
        StratifiedSample s;
        point(Dimension::film, at.subpixel_stream, at.round, s.film);
        point(Dimension::light, at.pixel_stream, at.round * round_ + at.subpixel, s.first.light);
        point(Dimension::bounce, at.pixel_stream, at.round * round_ + at.subpixel, s.first.bounce);
        return s;
    }
    // The film position of ray k of `rays` that sample `index` spends on the direct view
    // (direct_view.h): all of a subpixel's such rays are stratified together.
    void direct_view_film(uint32_t index, uint32_t rays, uint32_t k, double film[2]) const {
        const Position at = position(index);
        point(Dimension::direct_view, at.subpixel_stream, at.round * rays + k, film);
    }

private:
    // The stratified dimensions, each a key of its own (shifted into the key's top byte).
    enum class Dimension : uint64_t { film = 1, light = 2, bounce = 3, direct_view = 4 };

    // Where sample `index` lies: its subpixel, its round within its replicate, and the streams
    // of its replicate that cover the subpixel and the whole pixel.
    struct Position {
        uint32_t subpixel, round, subpixel_stream, pixel_stream;
    };
    Position position(uint32_t index) const {
        const uint32_t subpixel = index % round_, replicate = first_replicate(index, round_) ? 0 : 1;
        const uint32_t streams = replicate << sample_keys::kReplicateShift;
        return {subpixel, index / round_ / 2, streams | subpixel, streams | sample_keys::kWholePixel};
    }

    // Point `index` of dimension `dimension`'s sequence number `stream`, in the dimension's order.
    void point(Dimension dimension, uint32_t stream, uint32_t index, double u[2]) const {
        const uint64_t key = mix64(key_ ^ (uint64_t(dimension) << 56) ^ stream);
        sobol_2d(owen_scramble(index, mix64(key ^ sample_keys::kShuffle)), key, u[0], u[1]);
    }

    uint64_t key_;
    uint32_t round_;
};

}  // namespace glint
