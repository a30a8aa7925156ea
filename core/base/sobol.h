// Scrambled Sobol' points in two dimensions, for the samples whose stratification pays most
// (where in the pixel a camera ray goes, and the first diffuse vertex's light sample and
// bounce). Point i of the sequence depends only on (key, i), so sample ranges still split and
// merge, and any thread count gives the same image. Sobol's first two dimensions form a
// (0,2)-sequence: every power-of-two prefix puts one point in each cell of every 2^a × 2^b grid
// of that many cells. A nested scramble (Owen's kind: each bit flipped by a function of the bits
// above it) keeps that, randomises the points without bias, and makes the error of smooth
// integrands fall faster than with independent samples.
#pragma once

#include "base/rng.h"

namespace glint {

inline uint32_t reverse_bits(uint32_t i) {
    i = (i << 16) | (i >> 16);
    i = ((i & 0x00FF00FFu) << 8) | ((i & 0xFF00FF00u) >> 8);
    i = ((i & 0x0F0F0F0Fu) << 4) | ((i & 0xF0F0F0F0u) >> 4);
    i = ((i & 0x33333333u) << 2) | ((i & 0xCCCCCCCCu) >> 2);
    return ((i & 0x55555555u) << 1) | ((i & 0xAAAAAAAAu) >> 1);
}

// Dimension 0: the van der Corput sequence, i's bits reversed.
inline uint32_t sobol_dimension0(uint32_t i) { return reverse_bits(i); }

// Dimension 1: primitive polynomial x + 1, direction numbers v_k = v_(k-1) xor v_(k-1)/2, so
// v_k has the bit j places below the top set where the binomial C(k, j) is odd, that is where
// j's bits are a subset of k's (Lucas). Bit j of the point, counted from the top, is then the
// xor of i's bits k over the supersets k of j: a superset transform over the five bits of a
// position, done for all 32 positions at once in five shift-and-xor steps (step d folds in the
// positions that differ from j by bit d), then reversed so that position j lands j below the top.
// A loop over i's bits costs a branch per bit, and shuffled indices have all 32 bits.
inline uint32_t sobol_dimension1(uint32_t i) {
    i ^= (i >> 1) & 0x55555555u;
    i ^= (i >> 2) & 0x33333333u;
    i ^= (i >> 4) & 0x0F0F0F0Fu;
    i ^= (i >> 8) & 0x00FF00FFu;
    i ^= (i >> 16) & 0x0000FFFFu;
    return reverse_bits(i);
}

// Nested scrambling in the manner of Laine and Karras (2011): in bit-reversed order, where the
// point's top bit is the lowest, adding and multiplying carry only upwards, so each bit of the
// result is flipped by a function of the key and of the bits below it, i.e. of the dyadic
// interval the point lies in: the scramble is nested, and every elementary interval keeps its
// one point. Adding the key's low word first makes each point exactly uniform over keys (the
// rest are bijections). The multipliers are glint's own (SplitMix64 outputs; the even ones
// xor-shift, the odd one from the key permutes). About 20 instructions, against 32 hashes
// for a scramble that draws every bit's flip afresh; the price is flips that are less random
// (bench/run_sampler_comparison.sh measures the error it costs).
inline uint32_t owen_scramble(uint32_t x, uint64_t key) {
    constexpr uint32_t m1 = uint32_t(mix64(1)) & ~1u, m2 = uint32_t(mix64(2)) & ~1u, m3 = uint32_t(mix64(3)) & ~1u;
    uint32_t v = reverse_bits(x);
    v += uint32_t(key);
    v ^= v * m1;
    v *= uint32_t(key >> 32) | 1u;
    v ^= v * m2;
    v ^= v * m3;
    return reverse_bits(v);
}

// Point i of the 2D sequence with scrambling key `key`, each coordinate in [0, 1).
inline void sobol_2d(uint32_t i, uint64_t key, double& u1, double& u2) {
    u1 = owen_scramble(sobol_dimension0(i), mix64(key)) * 0x1p-32;
    u2 = owen_scramble(sobol_dimension1(i), mix64(key + 1)) * 0x1p-32;
}

}  // namespace glint
