// A render converges: its error keeps falling with the samples, on a scene where the image
// depends on the film position and the lighting together (a checker of triangles under a quad
// light, with a sphere's soft shadow across it), and the error estimate sees that error. The
// error is measured from pairs of renders with different seeds (testing::measure_by_pairs),
// which sees the part of it that depends on the seed.
#include <gtest/gtest.h>

#include <sstream>
#include <string>

#include "support/test_support.h"

namespace glint {
namespace {

// 16 × 16 squares, alternately light and dark, on the plane y = 0, 4 wide; a quad light above
// one side, a sphere between them. Seen from above at 24 × 24 pixels, most pixels hold a
// checker edge, a shadow edge, or both.
std::string checker_scene(const std::string& filter) {
    std::ostringstream light, dark;
    const int n = 16;
    const double size = 4.0 / n;
    for (int i = 0; i < n; ++i)
        for (int j = 0; j < n; ++j) {
            std::ostringstream& out = (i + j) % 2 ? dark : light;
            const double x = -2 + i * size, z = -2 + j * size;
            if (out.tellp() > 0) out << ",";
            out << "[" << x << ",0," << z << "],[" << x + size << ",0," << z << "],[" << x + size << ",0," << z + size
                << "],[" << x << ",0," << z + size << "]";
        }
    std::ostringstream indices;
    for (int q = 0; q < n * n / 2; ++q)
        indices << (q ? "," : "") << "[" << 4 * q << "," << 4 * q + 2 << "," << 4 * q + 1 << "],[" << 4 * q << ","
                << 4 * q + 3 << "," << 4 * q + 2 << "]";
    return R"({"camera": {"position": [0, 6, 0], "look_at": [0, 0, 0], "up": [0, 0, -1], "fov": 34},
        "film": {"width": 24, "height": 24, "filter": ")" + filter + R"("},
        "objects": [
          {"type": "mesh", "material": {"albedo": 0.8}, "vertices": [)" + light.str() + R"(], "indices": [)" +
           indices.str() + R"(]},
          {"type": "mesh", "material": {"albedo": 0.1}, "vertices": [)" + dark.str() + R"(], "indices": [)" +
           indices.str() + R"(]},
          {"type": "sphere", "center": [0.3, 0.9, 0.2], "radius": 0.5, "material": {"albedo": 0.5}},
          {"type": "mesh", "material": {"albedo": 0}, "emission": 8,
           "vertices": [[-1.5, 2.5, -1], [0.5, 2.5, -1], [0.5, 2.5, 1], [-1.5, 2.5, 1]],
           "indices": [[0, 1, 2], [0, 2, 3]]}]})";
}

class Convergence : public ::testing::TestWithParam<const char*> {};

// MSE × spp does not grow from 64 to 4096 spp (within the measurement's noise, a few percent
// here; it falls to 0.86 and 0.72 of its value): the error falls at least as fast as
// independent samples'. The estimate is within 3% of the measured error at both counts. With
// the film position and the light sample functions of each other, the same scene's MSE × spp
// grew 33× (box) and 32× (tent) over that range, 8× the error at 4096 spp, and the estimate
// said 0.25× and 0.22× of it.
TEST_P(Convergence, ErrorKeepsFallingWithTheSamples) {
    const LoadedScene scene = testing::scene_from(checker_scene(GetParam()));
    const testing::Measured low = testing::measure_by_pairs(scene, 64, 4), high = testing::measure_by_pairs(scene, 4096);
    const double growth = (high.rmse * high.rmse * 4096) / (low.rmse * low.rmse * 64);
    EXPECT_LT(growth, 1.15) << "RMSE at 64 spp " << low.rmse << ", at 4096 spp " << high.rmse;
    // The estimate sees the error at every sample count, not only at low ones.
    for (const testing::Measured& m : {low, high}) {
        const double ratio = m.estimate / m.rmse;
        EXPECT_TRUE(ratio < 1.5 && ratio > 1 / 1.5) << "estimated " << m.estimate << ", measured " << m.rmse;
    }
}

INSTANTIATE_TEST_SUITE_P(Filters, Convergence, ::testing::Values("box", "tent"));

}  // namespace
}  // namespace glint
