// Runs a program and collects what it prints: how the service talks to a farm's command-line
// tools (sbatch through docker/slurm/submit, squeue, scancel) without a shell in between.
#pragma once

#include <string>
#include <vector>

namespace glint {

// Runs argv (argv[0] looked up in PATH, no shell) to its end; returns its exit status, or -1 if
// it could not start or was killed by a signal. What it wrote to stdout and stderr is appended to
// `output`. The child starts with no signal blocked, whatever the calling thread blocks.
int run_command(const std::vector<std::string>& argv, std::string& output);

}  // namespace glint
