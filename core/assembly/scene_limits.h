// What one scene may ask for, and the error that names the JSON path a scene got wrong. Apart
// from scene_loader.h so that the film's checks (film_overrides.h) can use them without the
// loader, and the loader can use those checks.
#pragma once

#include <cstddef>
#include <cstdint>
#include <stdexcept>
#include <string>

namespace glint {

class SceneError : public std::runtime_error {
public:
    // malformed: the text is not acceptable JSON at all (syntax, nesting); otherwise the JSON is
    // fine but the scene it describes is not.
    SceneError(const std::string& path, const std::string& message, bool malformed = false)
        : std::runtime_error(path.empty() ? message : path + ": " + message),
          path_(path),
          message_(message),
          malformed_(malformed) {}
    const std::string& path() const { return path_; }
    const std::string& message() const { return message_; }
    bool malformed() const { return malformed_; }

private:
    std::string path_, message_;
    bool malformed_;
};

// Bounds on what one scene may ask for, so no input exhausts memory or runs forever.
struct SceneLimits {
    int max_dimension = 16384;
    int64_t max_pixels = int64_t(1) << 24;  // 16.7 Mpixel (about 1 GiB of film)
    uint32_t max_spp = 1u << 20;
    size_t max_objects = 100000;
    size_t max_triangles = 4000000;
    size_t max_file_bytes = size_t(512) << 20;
    double max_coordinate = 1e9;  // keeps squared distances far from overflow
    size_t max_texels_per_file = size_t(1) << 26;  // 8192 × 8192
    size_t max_texels = size_t(1) << 28;           // all of a scene's textures (1 GiB as 8-bit RGBA)
};

}  // namespace glint
