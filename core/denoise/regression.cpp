#include "denoise/regression.h"

#include <Eigen/Dense>
#include <cmath>

namespace glint {
namespace {

// The slopes' diagonal is raised by this share of itself (a ridge in each feature's own units,
// so a feature that varies little is not flattened more than one that varies much) and by
// kFloor of the total weight: a feature that does not vary in the window (a flat wall's normal)
// gets a slope of 0 instead of a singular system. The intercept is left alone.
constexpr double kRidge = 1e-3, kFloor = 1e-6;

}  // namespace

void RegressionSums::add(size_t i, double w, const std::array<float, kFeatures>& delta,
                         const std::array<float, 3>& colour) {
    std::array<double, kTerms> x;
    x[0] = 1;
    for (int j = 0; j < kFeatures; ++j) x[j + 1] = delta[j];
    double* s = &sums_[i * kStride];
    for (int r = 0; r < kTerms; ++r) {
        const double wx = w * x[r];
        for (int c = r; c < kTerms; ++c) *s++ += wx * x[c];
    }
    for (int c = 0; c < 3; ++c)
        for (int r = 0; r < kTerms; ++r) *s++ += w * x[r] * colour[c];
}

bool RegressionSums::solve(size_t i, std::array<float, 3>& colour) const {
    using Matrix = Eigen::Matrix<double, kTerms, kTerms>;
    const double* s = &sums_[i * kStride];
    if (!(s[0] > 0)) return false;
    Matrix a;
    for (int r = 0; r < kTerms; ++r)
        for (int c = r; c < kTerms; ++c) a(r, c) = a(c, r) = *s++;
    for (int j = 1; j < kTerms; ++j) a(j, j) = a(j, j) * (1 + kRidge) + kFloor * a(0, 0);
    const Eigen::Map<const Eigen::Matrix<double, kTerms, 3>> b(s);
    const Eigen::LDLT<Matrix> ldlt(a);
    if (ldlt.info() != Eigen::Success) return false;
    const Eigen::Matrix<double, kTerms, 3> beta = ldlt.solve(b);
    if (!beta.row(0).allFinite()) return false;
    for (int c = 0; c < 3; ++c) colour[c] = float(beta(0, c));
    return true;
}

}  // namespace glint
