#include "base/files.h"

#include <fcntl.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <filesystem>
#include <fstream>

namespace glint {
namespace {

// Writes all of `bytes` to `fd` and waits until they are on the disk.
bool write_and_sync(int fd, const std::vector<uint8_t>& bytes) {
    for (size_t done = 0; done < bytes.size();) {
        const ssize_t n = ::write(fd, bytes.data() + done, bytes.size() - done);
        if (n < 0 && errno == EINTR) continue;
        if (n <= 0) return false;
        done += size_t(n);
    }
    return ::fsync(fd) == 0;
}

// A rename is durable only once the folder holding the name is synced too.
void sync_folder(const std::filesystem::path& file) {
    const std::filesystem::path folder = file.has_parent_path() ? file.parent_path() : ".";
    const int fd = ::open(folder.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
    if (fd < 0) return;
    ::fsync(fd);
    ::close(fd);
}

}  // namespace

void write_file(const std::string& path, const std::vector<uint8_t>& bytes) {
    const std::string temporary = path + ".tmp";
    const int fd = ::open(temporary.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
    if (fd < 0) throw FileError("cannot write " + path + ": " + std::strerror(errno));
    const bool written = write_and_sync(fd, bytes);
    const int error_number = errno;
    if (::close(fd) != 0 || !written) {
        ::unlink(temporary.c_str());
        throw FileError("cannot write " + path + ": " + std::strerror(written ? errno : error_number));
    }
    std::error_code error;
    std::filesystem::rename(temporary, path, error);
    if (error) throw FileError("cannot write " + path + ": " + error.message());
    sync_folder(path);
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

std::string read_text(const std::filesystem::path& path, size_t max_bytes) {
    const std::vector<uint8_t> bytes = read_file(path.string(), max_bytes);
    return {bytes.begin(), bytes.end()};
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
