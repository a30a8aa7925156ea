// `glint merge`: one image from the partial files of a job split over machines.
#include <cstdio>

#include "assembly/film_exr.h"
#include "assembly/partial_file.h"
#include "base/files.h"
#include "cli/commands.h"

namespace glint {
namespace {

struct MergeOptions {
    std::string output, hdr, exr;
    std::vector<std::string> parts;
};

void declare_options(CLI::App& cmd, MergeOptions& o) {
    cmd.add_option("output", o.output, "PNG file to write")->required();
    cmd.add_option("parts", o.parts, "Partial files (glint render --partial)")->required();
    cmd.add_option("--hdr", o.hdr, "Also write the linear image as PFM");
    cmd.add_option("--exr", o.exr, "Also write an OpenEXR file: the linear image, sample counts, variance and any AOVs");
}

int run_merge(const MergeOptions& o) {
    std::vector<Partial> parts;
    for (const std::string& file : o.parts) {
        try {
            parts.push_back(decode_partial(read_file(file, size_t(8) << 30)));
        } catch (const std::exception& e) {
            throw PartialError(file + ": " + e.what());
        }
    }
    const Partial merged = merge_partials(std::move(parts));
    const Image image = merged.film.mean();
    write_file(o.output, encode_png(image, merged.encoding));
    if (!o.hdr.empty()) write_file(o.hdr, encode_pfm(image));
    if (!o.exr.empty()) write_file(o.exr, encode_film_exr(image, merged.film));
    std::printf("%s: %zu parts, samples [%u, %u) at %dx%d, estimated RMSE %.4g, "
                "%llu samples dropped (rounds with a non-finite one)\n",
                o.output.c_str(), o.parts.size(), merged.first_sample, merged.end_sample,
                merged.film.width(), merged.film.height(), merged.film.error_estimate(),
                static_cast<unsigned long long>(merged.film.dropped()));
    return 0;
}

}  // namespace

std::function<int()> add_merge_command(CLI::App& app) {
    return add_command<MergeOptions>(app, "merge", "Merge the partial files of one job into its image",
                                     declare_options, run_merge);
}

}  // namespace glint
