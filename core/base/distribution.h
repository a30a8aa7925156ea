// Piecewise-constant densities over [0, 1) and [0, 1)², sampled by inverting their cumulative
// sums: what an environment map's importance sampling draws from. Weights need not be
// normalised; a distribution whose weights are all zero samples uniformly, so that a caller
// never divides by zero (its pdf is then 1 everywhere).
#pragma once

#include <algorithm>
#include <cstddef>
#include <span>
#include <vector>

namespace glint {

class Distribution1D {
public:
    Distribution1D() = default;
    explicit Distribution1D(std::span<const double> weights) : cdf_(weights.size() + 1, 0.0) {
        for (size_t i = 0; i < weights.size(); ++i) cdf_[i + 1] = cdf_[i] + std::max(weights[i], 0.0);
        total_ = cdf_.back();
        const size_t n = weights.size();
        for (size_t i = 1; i <= n; ++i) cdf_[i] = total_ > 0 ? cdf_[i] / total_ : double(i) / double(n);
        cdf_.back() = 1;
    }

    size_t size() const { return cdf_.size() - 1; }
    double total() const { return total_; }  // the sum of the weights
    // The cell u falls in, u's position within it in [0, 1) (`within`), and the cell's density
    // over [0, 1).
    size_t sample(double u, double& within, double& pdf) const {
        const size_t cell = std::min<size_t>(std::upper_bound(cdf_.begin(), cdf_.end(), u) - cdf_.begin(), size()) - 1;
        const double width = cdf_[cell + 1] - cdf_[cell];
        within = width > 0 ? std::clamp((u - cdf_[cell]) / width, 0.0, kBelowOne) : 0.0;
        pdf = width * double(size());
        return cell;
    }
    double pdf(size_t cell) const { return (cdf_[cell + 1] - cdf_[cell]) * double(size()); }
    size_t memory_bytes() const { return sizeof(*this) + cdf_.capacity() * sizeof(double); }

private:
    static constexpr double kBelowOne = 0x1.fffffffffffffp-1;
    std::vector<double> cdf_{0.0, 1.0};
    double total_ = 0;
};

// Over a grid of width × height cells, row 0 first: a row by the marginal, then a column by
// that row's conditional.
class Distribution2D {
public:
    Distribution2D() = default;
    Distribution2D(std::span<const double> weights, size_t width, size_t height) {
        std::vector<double> row_totals(height);
        rows_.reserve(height);
        for (size_t j = 0; j < height; ++j) {
            rows_.emplace_back(weights.subspan(j * width, width));
            row_totals[j] = rows_.back().total();
        }
        marginal_ = Distribution1D(row_totals);
    }

    // A cell, u2 picking its row and u1 its column, and the place within it ([0, 1) each way).
    void sample(double u1, double u2, size_t& column, size_t& row, double& within_column, double& within_row) const {
        double pdf;
        row = marginal_.sample(u2, within_row, pdf);
        column = rows_[row].sample(u1, within_column, pdf);
    }
    // The density over [0, 1)² in the cell: its probability times the number of cells.
    double pdf(size_t column, size_t row) const { return marginal_.pdf(row) * rows_[row].pdf(column); }
    size_t memory_bytes() const {
        size_t bytes = marginal_.memory_bytes();
        for (const Distribution1D& row : rows_) bytes += row.memory_bytes();
        return bytes;
    }

private:
    std::vector<Distribution1D> rows_;
    Distribution1D marginal_;
};

}  // namespace glint
