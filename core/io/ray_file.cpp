#include "io/ray_file.h"

#include <bit>
#include <cstring>

#include "base/files.h"

namespace glint {
namespace {

static_assert(std::endian::native == std::endian::little, "ray files are little-endian");
constexpr size_t kHeader = 16;
constexpr size_t kMaxFileBytes = size_t(4) << 30;

template <typename Record>
std::vector<Record> read_records(const std::string& path, const char* magic) {
    const std::vector<uint8_t> bytes = read_file(path, kMaxFileBytes);
    uint64_t count = 0;
    if (bytes.size() < kHeader || std::memcmp(bytes.data(), magic, 8) != 0)
        throw FileError(path + ": not a " + std::string(magic, 8) + " file");
    std::memcpy(&count, bytes.data() + 8, 8);
    if (count != (bytes.size() - kHeader) / sizeof(Record) || (bytes.size() - kHeader) % sizeof(Record) != 0)
        throw FileError(path + ": record count does not match the file size");
    std::vector<Record> records(count);
    std::memcpy(records.data(), bytes.data() + kHeader, count * sizeof(Record));
    return records;
}

}  // namespace

std::vector<RayRecord> read_rays(const std::string& path) { return read_records<RayRecord>(path, "RAYS0001"); }
std::vector<HitRecord> read_hits(const std::string& path) { return read_records<HitRecord>(path, "HITS0001"); }

void write_hits(const std::string& path, const std::vector<HitRecord>& hits) {
    std::vector<uint8_t> bytes(kHeader + hits.size() * sizeof(HitRecord));
    const uint64_t count = hits.size();
    std::memcpy(bytes.data(), "HITS0001", 8);
    std::memcpy(bytes.data() + 8, &count, 8);
    std::memcpy(bytes.data() + kHeader, hits.data(), hits.size() * sizeof(HitRecord));
    write_file(path, bytes);
}

}  // namespace glint
