// Whole-file reads with a size bound, and writes that never leave half a file behind.
#pragma once

#include <cstdint>
#include <filesystem>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

namespace glint {

struct FileError : std::runtime_error {
    using std::runtime_error::runtime_error;
};

// Writes through a temporary file, fsync and a rename (then syncs the folder), so neither a
// reader nor a crash ever leaves half a file under `path`.
void write_file(const std::string& path, const std::vector<uint8_t>& bytes);
// Throws FileError if the file is missing, not a regular file, unreadable or larger than max_bytes.
std::vector<uint8_t> read_file(const std::string& path, size_t max_bytes);
// read_file's bytes as text.
std::string read_text(const std::filesystem::path& path, size_t max_bytes);

// `relative` resolved against `folder` (symlinks and ".." followed), or nothing when it is
// absolute, holds a NUL or resolves to a place outside the folder.
std::optional<std::filesystem::path> resolve_inside(const std::filesystem::path& folder, const std::string& relative);

}  // namespace glint
