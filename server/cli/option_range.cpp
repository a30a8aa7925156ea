#include "cli/option_range.h"

#include <charconv>
#include <cmath>
#include <sstream>

#include "base/thread_pool.h"

namespace glint {
namespace {

// Bounds as a person writes them: 3600, 0.5 (never 3.6e+03).
std::string number_text(double v) {
    std::ostringstream out;
    out.precision(15);
    out << v;
    return out.str();
}

// The whole of `text` as a T, or false (other characters, no digits, beyond T's range).
template <typename T>
bool parse_all(const std::string& text, T& value) {
    const char* end = text.data() + text.size();
    const auto [stop, error] = std::from_chars(text.data(), end, value);
    return error == std::errc() && stop == end;
}

}  // namespace

OptionRange integers(int64_t min, int64_t max) {
    return {"an integer in [" + std::to_string(min) + ", " + std::to_string(max) + "]",
            [min, max](const std::string& text) {
                int64_t v = 0;
                return parse_all(text, v) && v >= min && v <= max;
            }};
}

OptionRange numbers(double min, double max) {
    return {"a number in [" + number_text(min) + ", " + number_text(max) + "]",
            [min, max](const std::string& text) {
                double v = 0;
                return parse_all(text, v) && v >= min && v <= max;  // NaN fails both
            }};
}

OptionRange numbers_from(double min) {
    return {"a finite number >= " + number_text(min), [min](const std::string& text) {
                double v = 0;
                return parse_all(text, v) && std::isfinite(v) && v >= min;
            }};
}

OptionRange thread_count() { return integers(0, ThreadPool::kMaxThreads); }
OptionRange checkpoint_seconds() { return numbers(0, 3600); }

OptionRange film_option(FilmInteger field) {
    const IntegerRange range = film_range(field, SceneLimits{});
    return integers(range.min, range.max);
}

CLI::Option* in_range(CLI::Option* option, const OptionRange& range) {
    // CLI11 reports a refusal as "--name: " and the string the check returns, and shows the
    // check's description after the option's type in --help ("UINT:[0, 1024]").
    const std::string shown = range.text.substr(range.text.find_first_of("[>"));
    return option->check(CLI::Validator(
        [range](std::string& value) { return range.contains(value) ? "" : "must be " + range.text; }, shown));
}

}  // namespace glint
