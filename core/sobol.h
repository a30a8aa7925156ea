// Owen-scrambled Sobol' points in two dimensions, for the samples whose stratification pays
// most (where in the pixel a camera ray goes, and the first light sample). Point i of the
// sequence depends only on (key, i), so sample ranges still split and merge, and any thread
// count gives the same image. Sobol's first two dimensions form a (0,2)-sequence: every
// power-of-two prefix puts one point in each cell of every 2^a × 2^b grid of that many cells.
// Nested uniform (Owen) scrambling keeps that, randomises the points without bias, and makes
// the error of smooth integrands fall faster than with independent samples.
#pragma once

#include "rng.h"

namespace glint {

// Dimension 0: the van der Corput sequence, i's bits reversed.
inline uint32_t sobol_dimension0(uint32_t i) {
    i = (i << 16) | (i >> 16);
    i = ((i & 0x00FF00FFu) << 8) | ((i & 0xFF00FF00u) >> 8);
    i = ((i & 0x0F0F0F0Fu) << 4) | ((i & 0xF0F0F0F0u) >> 4);
    i = ((i & 0x33333333u) << 2) | ((i & 0xCCCCCCCCu) >> 2);
    return ((i & 0x55555555u) << 1) | ((i & 0xAAAAAAAAu) >> 1);
}

// Dimension 1: primitive polynomial x + 1, direction numbers v_k = v_(k-1) xor v_(k-1)/2.
inline uint32_t sobol_dimension1(uint32_t i) {
    uint32_t result = 0;
    for (uint32_t v = 0x80000000u; i != 0; i >>= 1, v ^= v >> 1)
        if (i & 1) result ^= v;
    return result;
}

// Nested uniform scrambling: bit b (from the top) is flipped or not by a random choice that
// depends on the key and on every bit above it, i.e. on the dyadic interval the point is in.
inline uint32_t owen_scramble(uint32_t x, uint64_t key) {
    uint32_t out = x;
    for (int level = 0; level < 32; ++level) {
        const int bit = 31 - level;
        const uint64_t above = level == 0 ? 0 : uint64_t(x >> (bit + 1));
        out ^= uint32_t(mix64(key ^ ((above << 6) | uint64_t(level))) & 1) << bit;
    }
    return out;
}

// Point i of the 2D sequence with scrambling key `key`, each coordinate in [0, 1).
inline void sobol_2d(uint32_t i, uint64_t key, double& u1, double& u2) {
    u1 = owen_scramble(sobol_dimension0(i), mix64(key)) * 0x1p-32;
    u2 = owen_scramble(sobol_dimension1(i), mix64(key + 1)) * 0x1p-32;
}

}  // namespace glint
