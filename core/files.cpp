#include "files.h"

#include <algorithm>
#include <fstream>

namespace glint {

void write_file(const std::string& path, const std::vector<uint8_t>& bytes) {
    const std::string temporary = path + ".tmp";
    {
        std::ofstream out(temporary, std::ios::binary);
        out.write(reinterpret_cast<const char*>(bytes.data()), std::streamsize(bytes.size()));
        if (!out) throw FileError("cannot write " + path);
    }
    std::error_code error;
    std::filesystem::rename(temporary, path, error);
    if (error) throw FileError("cannot write " + path + ": " + error.message());
}

std::vector<uint8_t> read_file(const std::string& path, size_t max_bytes) {
    std::error_code error;
    if (std::filesystem::exists(path, error) && !std::filesystem::is_regular_file(path, error))
        throw FileError(path + " is not a regular file");
    std::ifstream in(path, std::ios::binary | std::ios::ate);
    if (!in) throw FileError("cannot open " + path);
    const auto size = static_cast<size_t>(in.tellg());
    if (size > max_bytes) throw FileError(path + " is larger than " + std::to_string(max_bytes) + " bytes");
    std::vector<uint8_t> bytes(size);
    in.seekg(0);
    in.read(reinterpret_cast<char*>(bytes.data()), std::streamsize(size));
    if (!in) throw FileError("cannot read " + path);
    return bytes;
}

std::optional<std::filesystem::path> resolve_inside(const std::filesystem::path& folder, const std::string& relative) {
    const std::filesystem::path name = relative;
    if (relative.find('\0') != std::string::npos || name.has_root_path()) return std::nullopt;
    std::error_code error;
    const auto root = std::filesystem::weakly_canonical(folder, error);
    if (error) return std::nullopt;
    const auto full = std::filesystem::weakly_canonical(folder / name, error);
    if (error) return std::nullopt;
    const auto [end, _] = std::mismatch(root.begin(), root.end(), full.begin(), full.end());
    if (end != root.end()) return std::nullopt;
    return full;
}

}  // namespace glint
