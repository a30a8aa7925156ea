// The regression's fit on exact data: it recovers the intercept of a colour that is a linear
// function of the features, keeps the weighted mean where the features do not vary, and refuses
// a pixel with no weight.
#include <gtest/gtest.h>

#include "denoise/regression.h"

namespace glint {
namespace {

using Delta = std::array<float, kFeatures>;

TEST(Regression, RecoversTheInterceptOfALinearFunctionOfTheFeatures) {
    RegressionSums fit(2);
    for (int n = -3; n <= 3; ++n)
        for (int m = -3; m <= 3; ++m) {
            Delta delta{};
            delta[0] = 0.1f * float(n);  // an albedo channel
            delta[6] = 0.05f * float(m);  // depth
            const float value = 0.3f + 0.5f * delta[0] - 2.0f * delta[6];
            fit.add(1, 1.0 + 0.1 * (n * n + m), delta, {value, 2 * value, 0.0f});
        }
    std::array<float, 3> colour{};
    ASSERT_TRUE(fit.solve(1, colour));
    EXPECT_NEAR(colour[0], 0.3, 2e-3);
    EXPECT_NEAR(colour[1], 0.6, 4e-3);
    EXPECT_NEAR(colour[2], 0.0, 1e-6);
    EXPECT_FALSE(fit.solve(0, colour)) << "pixel 0 has no weight";
}

TEST(Regression, KeepsTheWeightedMeanWhereNoFeatureVaries) {
    RegressionSums fit(1);
    fit.add(0, 1.0, Delta{}, {1.0f, 0.0f, 0.0f});
    fit.add(0, 3.0, Delta{}, {0.0f, 1.0f, 0.0f});
    std::array<float, 3> colour{};
    ASSERT_TRUE(fit.solve(0, colour));
    EXPECT_NEAR(colour[0], 0.25, 1e-6);
    EXPECT_NEAR(colour[1], 0.75, 1e-6);
}

}  // namespace
}  // namespace glint
