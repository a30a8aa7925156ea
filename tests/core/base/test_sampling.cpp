// The samplers' own trigonometry against libm's.
#include <gtest/gtest.h>

#include "base/rng.h"
#include "base/sampling.h"

namespace glint {
namespace {

// Within 2^-51 of cos and sin of 2πu taken in long double (libm in double would be a worse
// reference: rounding 2πu alone moves its answer by up to 4e-16), at every octant boundary, just
// below each, and at random angles; exactly 1 and 0 where those are the answer.
TEST(Sampling, CosSinOfATurnAgreesWithLibm) {
    Rng rng(11, 0, 0);
    for (int i = 0; i < 200000; ++i) {
        const double u = i < 16 ? i / 16.0 : i < 32 ? std::nextafter((i - 15) / 16.0, 0.0) : rng.uniform();
        const CosSin got = cos_sin_2pi(u);
        const long double phi = 2 * 3.14159265358979323846264338327950288L * u;
        ASSERT_NEAR(got.cos, double(std::cos(phi)), 0x1p-51) << "u " << u;
        ASSERT_NEAR(got.sin, double(std::sin(phi)), 0x1p-51) << "u " << u;
        ASSERT_LE(got.cos * got.cos + got.sin * got.sin, 1 + 0x1p-50) << "u " << u;
    }
    EXPECT_EQ(cos_sin_2pi(0).cos, 1.0);
    EXPECT_EQ(cos_sin_2pi(0).sin, 0.0);
    EXPECT_EQ(cos_sin_2pi(0.25).cos, 0.0);
    EXPECT_EQ(cos_sin_2pi(0.25).sin, 1.0);
}

}  // namespace
}  // namespace glint
