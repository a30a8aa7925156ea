#include "files.h"

#include <filesystem>
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

}  // namespace glint
