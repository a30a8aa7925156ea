#include "denoise/denoiser.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <iterator>

#include "denoise/box_filter.h"
#include "denoise/denoiser_config.h"
#include "denoise/nl_means.h"

namespace glint {
namespace {

// Per channel, what a squared error at pixel i is divided by to make it relative: the square of
// the least of the pixel's values (its mean, each candidate's), plus a floor. A candidate that
// carries a bright neighbour's energy into a dark pixel is then judged by that pixel's own
// scale, as relMSE judges it; taking the least value keeps the scale from being the error it
// measures.
std::array<float, 3> error_scale(const HalfBuffers& h, const NlMeansOutput& fa, const NlMeansOutput& fb, size_t i,
                                 float floor) {
    std::array<float, 3> scale{};
    for (int c = 0; c < 3; ++c) {
        float least = std::abs(h.mean[c][i]);
        for (size_t k = 0; k < fa.filtered.size(); ++k)
            least = std::min(least, std::abs(fa.filtered[k][c][i] + fb.filtered[k][c][i]) / 2);
        scale[c] = 1 / (least * least + floor);
    }
    return scale;
}

float squared_distance(const Planes& x, const Planes& y, size_t i, const std::array<float, 3>& scale) {
    float sum = 0;
    for (int c = 0; c < 3; ++c) sum += (x[c][i] - y[c][i]) * (x[c][i] - y[c][i]) * scale[c] / 3;
    return sum;
}

// Per candidate (0: the unfiltered mean, then one per filter), per pixel: an estimate of its
// relative squared error plus the relative variance of a half. A half filtered with weights
// from itself is independent of the other half, so E[(F(A) - B)²] = MSE(F(A)) + Var(B), and
// E[(A - B)²] = Var(A) + Var(B).
std::vector<std::vector<float>> candidate_errors(const HalfBuffers& h, const NlMeansOutput& fa, const NlMeansOutput& fb,
                                                 float floor) {
    std::vector<std::vector<float>> errors(fa.filtered.size() + 1, std::vector<float>(h.mean[0].size()));
    for (size_t i = 0; i < errors[0].size(); ++i) {
        const std::array<float, 3> scale = error_scale(h, fa, fb, i, floor);
        errors[0][i] = squared_distance(h.a, h.b, i, scale);
        for (size_t k = 0; k < fa.filtered.size(); ++k)
            errors[k + 1][i] =
                (squared_distance(fa.filtered[k], h.b, i, scale) + squared_distance(fb.filtered[k], h.a, i, scale)) / 2;
    }
    return errors;
}

// Per candidate, per pixel: its weight in the pixel's blend, the inverse square of its error
// estimate averaged over the box around the pixel (one pixel's estimate has one degree of
// freedom per channel). The averaged estimates hold a half's variance V on top of each filtered
// candidate's error, and 2V for the unfiltered mean: a candidate's error is its estimate less V
// (at least kLeastError·V: an estimate can fall below it by noise), the unfiltered mean's is V.
// Weights are relative to the unfiltered mean's, 1; where V is 0 (no noise, or no halves yet)
// the pixel keeps its mean.
std::vector<std::vector<float>> blend_weights(const HalfBuffers& h, std::vector<std::vector<float>> errors,
                                              int radius) {
    constexpr double kLeastError = 1e-3;
    for (auto& error : errors) error = box_filter(error, h.width, h.height, radius);
    std::vector<std::vector<float>> weights(errors.size(), std::vector<float>(errors[0].size(), 0.0f));
    for (size_t i = 0; i < errors[0].size(); ++i) {
        const double v = double(errors[0][i]) / 2;
        weights[0][i] = 1;
        if (!(v > 0) || !std::isfinite(v)) continue;
        for (size_t k = 1; k < errors.size(); ++k) {
            const double error = std::max(double(errors[k][i]) - v, kLeastError * v);
            weights[k][i] = float(v * v / (error * error));
        }
    }
    return weights;
}

// Each pixel's value: the candidates weighted by their blend weights, a filtered
// candidate's value being the mean of its two filtered halves; then the splats added back.
Image blend(const HalfBuffers& h, const NlMeansOutput& fa, const NlMeansOutput& fb,
            const std::vector<std::vector<float>>& weights) {
    Image image(h.width, h.height);
    for (size_t i = 0; i < h.mean[0].size(); ++i)
        for (int c = 0; c < 3; ++c) {
            double value = weights[0][i] * h.mean[c][i], total = weights[0][i];
            for (size_t k = 1; k < weights.size(); ++k) {
                value += weights[k][i] * (fa.filtered[k - 1][c][i] + fb.filtered[k - 1][c][i]) / 2;
                total += weights[k][i];
            }
            const double blended = value / total;
            image.rgb[i * 3 + c] = float((std::isfinite(blended) && total > 0 ? blended : h.mean[c][i]) + h.splats[c][i]);
        }
    return image;
}

// What of the config this film can use: without AOVs, no candidate that needs them; in a film's
// first round (no pixel has both halves, so no variance to filter by), none at all.
DenoiserConfig usable_config(const HalfBuffers& halves, DenoiserConfig config) {
    const auto known = [](float v) { return v < kUnknownVariance; };
    const bool any_known = std::any_of(halves.half_variance.begin(), halves.half_variance.end(), known);
    for (DenoiserConfig::Filter& filter : config.filters) {
        if (!halves.has_features())
            std::erase_if(filter.candidates,
                          [](const DenoiserConfig::Candidate& k) { return k.feature > 0 || k.regression; });
        if (!any_known) filter.candidates.clear();
    }
    return config;
}

// One half filtered by every candidate of every filter, in the config's order.
NlMeansOutput filter_half(const HalfBuffers& h, const Planes& half, const std::vector<std::vector<float>>* features,
                          const DenoiserConfig& config, ThreadPool& pool) {
    NlMeansOutput out;
    for (const DenoiserConfig::Filter& filter : config.filters) {
        NlMeansOutput part = nl_means({h.width, h.height, &half, &h.half_variance, features, &h.feature_variance},
                                      filter, config, pool);
        std::move(part.filtered.begin(), part.filtered.end(), std::back_inserter(out.filtered));
    }
    return out;
}

}  // namespace

Image denoise(const Film& film, ThreadPool& pool) { return denoise_with(half_buffers(film), DenoiserConfig{}, pool); }

Image denoise(const HalfBuffers& halves, ThreadPool& pool) { return denoise_with(halves, DenoiserConfig{}, pool); }

Image denoise_with(const HalfBuffers& halves, const DenoiserConfig& config, ThreadPool& pool) {
    const DenoiserConfig usable = usable_config(halves, config);
    const bool features = halves.has_features();
    const NlMeansOutput fa = filter_half(halves, halves.a, features ? &halves.features_a : nullptr, usable, pool);
    const NlMeansOutput fb = filter_half(halves, halves.b, features ? &halves.features_b : nullptr, usable, pool);
    const auto errors = candidate_errors(halves, fa, fb, usable.relative_error_floor);
    return blend(halves, fa, fb, blend_weights(halves, errors, usable.selection_radius));
}

}  // namespace glint
