// Scrambled Sobol' points: stratification that survives the scrambling, and different keys
// giving different points.
#include <gtest/gtest.h>

#include <cmath>
#include <set>

#include "base/sobol.h"

namespace glint {
namespace {

TEST(Sobol, EveryPowerOfTwoBlockFillsEveryElementaryInterval) {
    // A (0,2)-sequence: for every block of 2^m consecutive points starting at a multiple of 2^m
    // and every split 2^a × 2^(m-a), each cell holds exactly one point.
    for (uint64_t key : {uint64_t(1), uint64_t(0xDEADBEEF)})
        for (int m : {4, 6}) {
            const uint32_t n = 1u << m;
            for (uint32_t start : {0u, n, 5 * n})
                for (int a = 0; a <= m; ++a) {
                    std::set<uint32_t> cells;
                    for (uint32_t i = start; i < start + n; ++i) {
                        double u1, u2;
                        sobol_2d(i, key, u1, u2);
                        ASSERT_TRUE(u1 >= 0 && u1 < 1 && u2 >= 0 && u2 < 1);
                        cells.insert(uint32_t(u1 * (1u << a)) * (1u << (m - a)) + uint32_t(u2 * (1u << (m - a))));
                    }
                    EXPECT_EQ(cells.size(), n) << "m " << m << " a " << a << " start " << start;
                }
        }
}

// The second dimension by its definition: the xor of the direction numbers v_k of i's set bits,
// v_0 = 2^31 and v_k = v_(k-1) xor v_(k-1)/2.
uint32_t sobol_dimension1_by_definition(uint32_t i) {
    uint32_t result = 0;
    for (uint32_t v = 0x80000000u; i != 0; i >>= 1, v ^= v >> 1)
        if (i & 1) result ^= v;
    return result;
}

TEST(Sobol, SecondDimensionIsTheDirectionNumbersXor) {
    for (uint32_t i = 0; i < 70000; ++i) ASSERT_EQ(sobol_dimension1(i), sobol_dimension1_by_definition(i)) << i;
    uint64_t state = 1;
    for (int n = 0; n < 100000; ++n) {
        const uint32_t i = uint32_t(mix64(state++));
        ASSERT_EQ(sobol_dimension1(i), sobol_dimension1_by_definition(i)) << i;
    }
}

TEST(Sobol, KeysScrambleDifferentlyAndTheMeanIsAHalf) {
    double a1, a2, b1, b2;
    sobol_2d(3, 1, a1, a2);
    sobol_2d(3, 2, b1, b2);
    EXPECT_NE(a1, b1);
    EXPECT_NE(a2, b2);
    // Over many keys a fixed index is uniform: its mean is 1/2 (Owen scrambling is unbiased).
    double sum = 0;
    const int keys = 20000;
    for (int k = 0; k < keys; ++k) {
        double u1, u2;
        sobol_2d(7, uint64_t(k), u1, u2);
        sum += u1 + u2;
    }
    EXPECT_NEAR(sum / (2 * keys), 0.5, 4 * std::sqrt(1.0 / 12 / (2 * keys)));
}

}  // namespace
}  // namespace glint

namespace glint {
namespace {

// Over keys, a fixed point must be uniform in every top-level stratum, not only on average:
// the eighths of [0, 1) in each coordinate, and the 4x4 cells of the square, each get their
// share (a scramble that left a high bit to the index would empty half of them).
TEST(Sobol, AFixedPointIsUniformOverKeysInEveryCoarseCell) {
    const int keys = 32000;
    for (uint32_t index : {0u, 5u, 1000u}) {
        std::vector<int> cells(16), eighths(8);
        for (int k = 0; k < keys; ++k) {
            double u1, u2;
            sobol_2d(index, mix64(uint64_t(k)), u1, u2);
            ++cells[size_t(u1 * 4) * 4 + size_t(u2 * 4)];
            ++eighths[size_t(u1 * 8)];
        }
        for (int c : cells) EXPECT_NEAR(c, keys / 16, 5 * std::sqrt(keys / 16.0)) << "index " << index;
        for (int c : eighths) EXPECT_NEAR(c, keys / 8, 5 * std::sqrt(keys / 8.0)) << "index " << index;
    }
}

}  // namespace
}  // namespace glint
