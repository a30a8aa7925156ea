// The ranges of the numeric options of every glint command. Each option's range is checked by
// CLI11 on the text given, before the value is converted, so a value outside it (or no number
// at all) is refused with one line naming the option and the range, "--threads: must be an
// integer in [0, 1024]", and CLI11's exit code for a value that fails its check (105) instead of
// a wrapped-around number, a failed conversion or an abort deep inside. --help shows each range.
#pragma once

#include <cstdint>
#include <functional>
#include <string>

#include <CLI/CLI.hpp>

#include "assembly/film_overrides.h"

namespace glint {

// What an option accepts, said and checked on the text given.
struct OptionRange {
    std::string text;  // "an integer in [0, 1024]", "a number in [0, 3600]", "a finite number >= 0"
    std::function<bool(const std::string&)> contains;
};

// Integers in [min, max], numbers in [min, max] (finite), finite numbers from min on.
OptionRange integers(int64_t min, int64_t max);
OptionRange numbers(double min, double max);
OptionRange numbers_from(double min);

// The same range for the same kind of option in every command.
OptionRange thread_count();       // [0, ThreadPool::kMaxThreads], 0: one per core
OptionRange checkpoint_seconds();  // [0, 3600], 0: after every pass
OptionRange film_option(FilmInteger field);  // as a scene file's film field (assembly/film_overrides.h)

// Checks `option` against `range` and shows the range in its --help line.
CLI::Option* in_range(CLI::Option* option, const OptionRange& range);

}  // namespace glint
