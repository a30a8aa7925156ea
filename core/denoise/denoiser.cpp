#include "denoise/denoiser.h"

#include "denoise/box_filter.h"
#include "denoise/nl_means.h"

namespace glint {
namespace {

float squared_distance(const Planes& x, const Planes& y, size_t i) {
    float sum = 0;
    for (int c = 0; c < 3; ++c) sum += (x[c][i] - y[c][i]) * (x[c][i] - y[c][i]) / 3;
    return sum;
}

// Per candidate (0: the unfiltered mean, then one per strength), per pixel: an estimate of its
// squared error plus the variance of a half, box-averaged. A half filtered with weights from
// itself is independent of the other half, so E[(F(A) - B)²] = MSE(F(A)) + Var(B). The splats
// are in both halves, so their noise is missing from (A - B)² and counts against a filter that
// removes it from (F(A) - B)²: with s the pixel's own weight in F, that term's expectation is
// (1 - 2s) times the splats' variance too high; both are put right.
std::vector<std::vector<float>> candidate_errors(const HalfBuffers& h, const NlMeansOutput& fa,
                                                 const NlMeansOutput& fb, int radius) {
    std::vector<std::vector<float>> errors(fa.filtered.size() + 1, std::vector<float>(h.mean[0].size()));
    for (size_t i = 0; i < errors[0].size(); ++i) {
        errors[0][i] = squared_distance(h.a, h.b, i) + h.splat_variance[i];
        for (size_t k = 0; k < fa.filtered.size(); ++k) {
            const float own = (fa.self_weight[k][i] + fb.self_weight[k][i]) / 2;
            errors[k + 1][i] = (squared_distance(fa.filtered[k], h.b, i) + squared_distance(fb.filtered[k], h.a, i)) / 2 -
                               (1 - 2 * own) * h.splat_variance[i];
        }
    }
    for (auto& error : errors) error = box_filter(error, h.width, h.height, radius);
    return errors;
}

// Each pixel's value from the candidate of least estimated error, the unfiltered mean on a tie:
// a filtered candidate's value is the mean of its two filtered halves.
Image select(const HalfBuffers& h, const NlMeansOutput& fa, const NlMeansOutput& fb,
             const std::vector<std::vector<float>>& errors) {
    Image image(h.width, h.height);
    for (size_t i = 0; i < h.mean[0].size(); ++i) {
        size_t best = 0;
        for (size_t k = 1; k < errors.size(); ++k)
            if (errors[k][i] < errors[best][i]) best = k;
        for (int c = 0; c < 3; ++c) {
            const float value = best == 0 ? h.mean[c][i] : (fa.filtered[best - 1][c][i] + fb.filtered[best - 1][c][i]) / 2;
            image.rgb[i * 3 + c] = std::isfinite(value) ? value : h.mean[c][i];
        }
    }
    return image;
}

}  // namespace

Image denoise(const Film& film, const DenoiserConfig& config, ThreadPool& pool) {
    return denoise(half_buffers(film), config, pool);
}

Image denoise(const HalfBuffers& halves, const DenoiserConfig& config, ThreadPool& pool) {
    const NlMeansOutput fa = nl_means({halves.width, halves.height, &halves.a, &halves.half_variance}, config, pool);
    const NlMeansOutput fb = nl_means({halves.width, halves.height, &halves.b, &halves.half_variance}, config, pool);
    return select(halves, fa, fb, candidate_errors(halves, fa, fb, config.selection_radius));
}

}  // namespace glint
