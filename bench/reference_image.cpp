#include "reference_image.h"

#include <cstdio>
#include <filesystem>

#include "base/files.h"
#include "io/image_io.h"
#include "render/renderer.h"

namespace glint {

Image reference_image(LoadedScene loaded, const std::string& folder, uint32_t spp, unsigned threads) {
    const auto& s = loaded.settings;
    const std::filesystem::path file = std::filesystem::path(folder) / ("reference-" + std::to_string(s.width) + "x" +
                                                                        std::to_string(s.height) + "-" +
                                                                        std::to_string(spp) + "spp.pfm");
    if (std::filesystem::exists(file)) return decode_pfm(read_file(file.string(), size_t(1) << 30));
    loaded.settings.spp = spp;
    loaded.settings.seed = 0x5EED;
    ThreadPool pool(threads);
    RenderJob job(loaded.scene, loaded.settings);
    std::fprintf(stderr, "rendering reference %s at %u spp...\n", file.c_str(), spp);
    job.run(pool);
    std::fprintf(stderr, "reference done in %.0f s, its own estimated RMSE %.4g\n", job.progress().seconds,
                 job.film().error_estimate());
    write_file(file.string(), encode_pfm(job.film().mean()));
    const std::string estimate = std::to_string(job.film().error_estimate()) + "\n";
    write_file(file.string() + ".estimate", std::vector<uint8_t>(estimate.begin(), estimate.end()));
    return job.film().mean();
}

}  // namespace glint
