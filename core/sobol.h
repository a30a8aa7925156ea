// Scrambled Sobol' points in two dimensions, for the samples whose stratification pays most
// (where in the pixel a camera ray goes, and the first diffuse vertex's light sample and
// bounce). Point i of the sequence depends only on (key, i), so sample ranges still split and
// merge, and any thread count gives the same image. Sobol's first two dimensions form a
// (0,2)-sequence: every power-of-two prefix puts one point in each cell of every 2^a × 2^b grid
// of that many cells. A nested scramble (Owen's kind: each bit flipped by a function of the bits
// above it) keeps that, randomises the points without bias, and makes the error of smooth
// integrands fall faster than with independent samples.
#pragma once

#include "rng.h"

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

// Dimension 1: primitive polynomial x + 1, direction numbers v_k = v_(k-1) xor v_(k-1)/2.
inline uint32_t sobol_dimension1(uint32_t i) {
    uint32_t result = 0;
    for (uint32_t v = 0x80000000u; i != 0; i >>= 1, v ^= v >> 1)
        if (i & 1) result ^= v;
    return result;
}

// Nested scrambling in the manner of Laine and Karras (2011): in bit-reversed order, where the
// point's top bit is the lowest, adding and multiplying carry only upwards, so each bit of the
// result is flipped by a function of the key and of the bits below it, i.e. of the dyadic
// interval the point lies in: the scramble is nested, and every elementary interval keeps its
// one point. Adding the key's low word first makes each point exactly uniform over keys (the
// rest are bijections). The multipliers are glint's own (SplitMix64 outputs; the even ones
// xor-shift, the odd one from the key permutes). About 20 instructions, against 32 hashes
// for a scramble that draws every bit's flip afresh; which flips it draws is less random, and
// what that costs is measured in bench/BENCHMARKS.md.
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
