#include "cli/progress_bar.h"

#include <unistd.h>

#include <string>

#include "service/progress_json.h"

namespace glint {

ProgressBar::ProgressBar(std::FILE* out) : out_(out), interactive_(isatty(fileno(out)) != 0) {}

void ProgressBar::update(const Progress& p) {
    const double fraction = p.spp_target > 0 ? double(p.spp_done) / p.spp_target : 1;
    const double eta = eta_seconds(p);
    char figures[160];
    std::snprintf(figures, sizeof figures, "%u/%u spp  %.1fs  ETA %.1fs  %.2f Msamples/s  error %.4g", p.spp_done,
                  p.spp_target, p.seconds, eta, p.samples_per_second / 1e6, p.error_estimate);
    if (!interactive_) {
        std::fprintf(out_, "progress %3.0f%%  %s\n", 100 * fraction, figures);
        std::fflush(out_);
        return;
    }
    constexpr int kWidth = 30;
    const int filled = int(fraction * kWidth);
    std::string bar(size_t(filled), '#');
    bar.append(size_t(kWidth - filled), '.');
    std::fprintf(out_, "\r[%s] %3.0f%%  %s\x1b[K", bar.c_str(), 100 * fraction, figures);
    std::fflush(out_);
    drawn_ = true;
}

void ProgressBar::finish() {
    if (drawn_) std::fputc('\n', out_);
    drawn_ = false;
}

}  // namespace glint
