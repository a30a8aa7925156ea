// The subcommands of the glint executable.
#pragma once

#include <cstdio>
#include <exception>
#include <functional>
#include <memory>

#include <CLI/CLI.hpp>

namespace glint {

// Each adds its subcommand to `app`; the returned function runs it and gives the exit code.
std::function<int()> add_render_command(CLI::App& app);
std::function<int()> add_trace_rays_command(CLI::App& app);
std::function<int()> add_serve_command(CLI::App& app);
std::function<int()> add_merge_command(CLI::App& app);

// Runs a command's work: an exception ends it with exit code 1 and its message on stderr, so a
// bad file or argument reads "glint: WHY" and never as an abort.
template <typename Work>
int run_reporting_errors(Work&& work) {
    try {
        return work();
    } catch (const std::exception& e) {
        std::fprintf(stderr, "glint: %s\n", e.what());
        return 1;
    }
}

// Adds subcommand `name` whose options `declare(command, options)` binds to an Options; the
// returned function runs `run(options)` under run_reporting_errors.
template <typename Options, typename Declare, typename Run>
std::function<int()> add_command(CLI::App& app, const char* name, const char* description,
                                 Declare declare, Run run) {
    auto options = std::make_shared<Options>();
    declare(*app.add_subcommand(name, description), *options);
    return [options, run] { return run_reporting_errors([&] { return run(*options); }); };
}

}  // namespace glint
