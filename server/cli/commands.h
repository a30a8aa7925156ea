// The subcommands of the glint executable.
#pragma once

#include <functional>

#include <CLI/CLI.hpp>

namespace glint {

// Each adds its subcommand to `app`; the returned function runs it and gives the exit code.
std::function<int()> add_render_command(CLI::App& app);
std::function<int()> add_trace_rays_command(CLI::App& app);
std::function<int()> add_serve_command(CLI::App& app);
std::function<int()> add_merge_command(CLI::App& app);

}  // namespace glint
