// glint: a Monte-Carlo path tracer as a batch command and a render service.
#include <cstdio>
#include <map>

#include "cli/commands.h"
#include "cli/huge_pages.h"

int main(int argc, char** argv) {
    if (!__builtin_cpu_supports("avx2") || !__builtin_cpu_supports("fma")) {  // built with -mavx2 -mfma (see CMakeLists.txt)
        std::fprintf(stderr, "glint: this processor lacks AVX2 or FMA, which this build of glint needs\n");
        return 1;
    }
    glint::request_huge_pages(argv);
    CLI::App app{"glint: a path-tracing renderer"};
    app.require_subcommand(1);
    const std::map<std::string, std::function<int()>> commands = {
        {"render", glint::add_render_command(app)},
        {"serve", glint::add_serve_command(app)},
        {"merge", glint::add_merge_command(app)},
        {"trace-rays", glint::add_trace_rays_command(app)},
    };
    CLI11_PARSE(app, argc, argv);
    for (const auto& [name, run] : commands)
        if (app.got_subcommand(name)) return run();
    return 2;
}
