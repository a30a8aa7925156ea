// Small image files made in memory, and a scratch folder to put them in, for the tests of
// textures and of the scenes that use them.
#pragma once

#include <gtest/gtest.h>
#include <stb_image_write.h>
#include <unistd.h>

#include <filesystem>
#include <string>
#include <vector>

#include "base/files.h"
#include "io/exr_file.h"

namespace glint::testing {

inline void append_bytes(void* context, void* data, int size) {
    auto* out = static_cast<std::vector<uint8_t>*>(context);
    out->insert(out->end(), static_cast<uint8_t*>(data), static_cast<uint8_t*>(data) + size);
}

// texels: rows top first, `channels` bytes each.
inline std::vector<uint8_t> png(int width, int height, int channels, const std::vector<uint8_t>& texels) {
    std::vector<uint8_t> out;
    EXPECT_TRUE(stbi_write_png_to_func(append_bytes, &out, width, height, channels, texels.data(), width * channels));
    return out;
}

// One plane of width·height floats (rows top first) per channel.
inline std::vector<uint8_t> exr(int width, int height, std::vector<std::string> channels,
                                std::vector<std::vector<float>> planes) {
    return encode_exr(width, height, {ExrLayer{"", std::move(channels), std::move(planes)}});
}

// A folder of its own under the system's temporary folder, removed with everything in it.
class ScratchFolder {
public:
    explicit ScratchFolder(const std::string& name)
        : path_(std::filesystem::temp_directory_path() / (name + "-" + std::to_string(::getpid()))) {
        std::filesystem::remove_all(path_);
        std::filesystem::create_directories(path_);
    }
    ~ScratchFolder() { std::filesystem::remove_all(path_); }
    ScratchFolder(const ScratchFolder&) = delete;
    ScratchFolder& operator=(const ScratchFolder&) = delete;

    const std::filesystem::path& path() const { return path_; }
    void write(const std::string& name, const std::vector<uint8_t>& bytes) const { write_file((path_ / name).string(), bytes); }

private:
    std::filesystem::path path_;
};

}  // namespace glint::testing
