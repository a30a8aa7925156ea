#include "denoise/nl_means.h"

#include <algorithm>
#include <cmath>
#include <optional>

#include "denoise/box_filter.h"
#include "denoise/half_buffers.h"
#include "denoise/regression.h"

namespace glint {
namespace {

constexpr int kBandRows = 16;  // rows per task: a band recomputes patch_radius rows on each side

struct Offset {
    int dx, dy;
};

// The weight sums of one band of rows, per candidate: Σw and Σw·value per channel, and for a
// candidate that fits a regression, its normal equations.
struct BandSums {
    std::vector<std::array<std::vector<double>, 4>> sums;
    std::vector<std::optional<RegressionSums>> fits;
    BandSums(const DenoiserConfig::Filter& filter, size_t pixels) : sums(filter.candidates.size()), fits(sums.size()) {
        for (size_t k = 0; k < sums.size(); ++k) {
            for (auto& plane : sums[k]) plane.assign(pixels, 0.0);
            if (filter.candidates[k].regression) fits[k].emplace(pixels);
        }
    }
};

// Pixel q's features less pixel p's, and q's colour: what a regression adds for the pair.
void add_to_fit(const NlMeansInput& in, size_t p, size_t q, size_t out, double weight, RegressionSums& fit) {
    std::array<float, kFeatures> delta;
    for (int j = 0; j < kFeatures; ++j) delta[j] = (*in.features)[j][q] - (*in.features)[j][p];
    fit.add(out, weight, delta, {(*in.image)[0][q], (*in.image)[1][q], (*in.image)[2][q]});
}

// Per pixel of rows [y0, y1), for neighbour offset o (clamped at the border): the squared
// difference of the two pixels, mean over channels, less the share noise explains, and twice
// the variance of the pixel p being filtered; then both averaged over the patch. The distance
// is measured in units of p's own noise, not of the two pixels' together: with the sum, a
// neighbour made very noisy by a firefly looks like anything and a quiet dark pixel takes a share
// of its energy (a halo the error estimates then keep where the firefly's own error dominates
// the box they average over), while a noisy pixel still takes its quieter neighbours.
void patch_terms(const NlMeansInput& in, const DenoiserConfig::Filter& filter, const DenoiserConfig& config, Offset o,
                 int y0, int y1, std::vector<float>& distance, std::vector<float>& variance) {
    const int w = in.width;
    const auto& var = *in.variance;
    distance.resize(size_t(y1 - y0) * w);
    variance.resize(distance.size());
    for (int y = y0; y < y1; ++y)
        for (int x = 0; x < w; ++x) {
            const size_t p = size_t(y) * w + x;
            const size_t q = size_t(std::clamp(y + o.dy, 0, in.height - 1)) * w + std::clamp(x + o.dx, 0, w - 1);
            float d = 0;
            for (int c = 0; c < 3; ++c) {
                const float diff = (*in.image)[c][p] - (*in.image)[c][q];
                d += diff * diff / 3;
            }
            const size_t i = size_t(y - y0) * w + x;
            distance[i] = d - config.variance_cancel * (var[p] + std::min(var[p], var[q]));
            variance[i] = 2 * var[p];
        }
    distance = box_filter(distance, w, y1 - y0, filter.patch_radius);
    variance = box_filter(variance, w, y1 - y0, filter.patch_radius);
}

// The largest over the feature planes of their squared difference between pixels p and q, less
// what noise explains, in units of their variance (at least the config's floor).
float feature_distance(const NlMeansInput& in, float floor, size_t p, size_t q) {
    float worst = 0;
    for (size_t j = 0; j < in.features->size(); ++j) {
        const std::vector<float>& f = (*in.features)[j];
        const std::vector<float>& v = (*in.feature_variance)[j];
        const float d = f[p] - f[q];
        worst = std::max(worst, (d * d - (v[p] + std::min(v[p], v[q]))) / std::max(floor, v[p] + v[q]));
    }
    return worst;
}

// A candidate's weight: the lesser of the colour and the feature weights it uses.
double candidate_weight(const DenoiserConfig::Candidate& k, float colour_distance, float colour_variance,
                        float feature) {
    double weight = 1;
    if (k.colour > 0)
        weight = std::exp(-double(std::max(0.0f, colour_distance) / (k.colour * k.colour * colour_variance + 1e-20f)));
    if (k.feature > 0) weight = std::min(weight, std::exp(-double(feature / (k.feature * k.feature))));
    return weight;
}

// Adds neighbour offset o's weighted values to the band [y0, y1)'s sums.
void add_offset(const NlMeansInput& in, const DenoiserConfig::Filter& filter, const DenoiserConfig& config, Offset o,
                int y0, int y1, BandSums& band) {
    const int w = in.width, r = filter.patch_radius;
    const int ey0 = std::max(0, y0 - r), ey1 = std::min(in.height, y1 + r);
    std::vector<float> distance, variance;
    patch_terms(in, filter, config, o, ey0, ey1, distance, variance);
    for (int y = std::max(y0, -o.dy); y < std::min(y1, in.height - o.dy); ++y)
        for (int x = std::max(0, -o.dx); x < std::min(w, w - o.dx); ++x) {
            const size_t q = size_t(y + o.dy) * w + x + o.dx, i = size_t(y - ey0) * w + x;
            if ((*in.variance)[q] >= kUnknownVariance) continue;
            const size_t out = size_t(y - y0) * w + x, p = size_t(y) * w + x;
            const float feature = in.features ? feature_distance(in, config.feature_floor, p, q) : 0;
            for (size_t k = 0; k < filter.candidates.size(); ++k) {
                const double weight = candidate_weight(filter.candidates[k], distance[i], variance[i], feature);
                auto& sums = band.sums[k];
                sums[3][out] += weight;
                for (int c = 0; c < 3; ++c) sums[c][out] += weight * (*in.image)[c][q];
                if (band.fits[k]) add_to_fit(in, p, q, out, weight, *band.fits[k]);
            }
        }
}

// The band's filtered values: the weighted mean, or a regression's fit where the candidate has
// one and it can be solved; the pixel itself where its variance is unknown.
void finish_band(const NlMeansInput& in, int y0, int y1, const BandSums& band, NlMeansOutput& out) {
    const int w = in.width;
    for (size_t k = 0; k < band.sums.size(); ++k)
        for (size_t i = 0; i < size_t(y1 - y0) * w; ++i) {
            const size_t p = size_t(y0) * w + i;
            const auto& sums = band.sums[k];
            const bool known = (*in.variance)[p] < kUnknownVariance && sums[3][i] > 0;
            std::array<float, 3> value;
            for (int c = 0; c < 3; ++c) value[c] = known ? float(sums[c][i] / sums[3][i]) : (*in.image)[c][p];
            if (known && band.fits[k]) band.fits[k]->solve(i, value);
            for (int c = 0; c < 3; ++c) out.filtered[k][c][p] = value[c];
        }
}

}  // namespace

NlMeansOutput nl_means(const NlMeansInput& in, const DenoiserConfig::Filter& filter, const DenoiserConfig& config,
                       ThreadPool& pool) {
    const size_t pixels = size_t(in.width) * in.height, candidates = filter.candidates.size();
    NlMeansOutput out;
    if (candidates == 0) return out;
    out.filtered.resize(candidates);
    for (Planes& planes : out.filtered)
        for (auto& plane : planes) plane.resize(pixels);
    const int r = filter.window_radius;
    const size_t bands = size_t(in.height + kBandRows - 1) / kBandRows;
    pool.parallel_for(bands, [&](size_t band_index) {
        const int y0 = int(band_index) * kBandRows, y1 = std::min(in.height, y0 + kBandRows);
        BandSums band(filter, size_t(y1 - y0) * in.width);
        for (int dy = -r; dy <= r; ++dy)
            for (int dx = -r; dx <= r; ++dx) add_offset(in, filter, config, {dx, dy}, y0, y1, band);
        finish_band(in, y0, y1, band, out);
    });
    return out;
}

}  // namespace glint
