#include "assembly/partial_file.h"

#include <stdexcept>

#include <algorithm>
#include <bit>
#include <cstring>
#include <string>

#include "assembly/fingerprint.h"

namespace glint {
namespace {

static_assert(std::endian::native == std::endian::little, "partial files are little-endian");
constexpr char kMagic[8] = {'G', 'L', 'N', 'T', 'P', 'A', 'R', 'T'};
constexpr uint32_t kVersion = 5;
constexpr size_t kHeader = 56, kPixel = 128, kAovPixel = 112, kTrailer = 8;
constexpr uint32_t kHasAovs = 1;

class Writer {
public:
    template <typename T>
    void put(const T& v) {
        const auto* p = reinterpret_cast<const uint8_t*>(&v);
        bytes.insert(bytes.end(), p, p + sizeof v);
    }
    std::vector<uint8_t> bytes;
};

class Reader {
public:
    explicit Reader(const std::vector<uint8_t>& b) : bytes_(b) {}
    template <typename T>
    T get() {
        T v;
        std::memcpy(&v, &bytes_[at_], sizeof v);
        at_ += sizeof v;
        return v;
    }

private:
    const std::vector<uint8_t>& bytes_;
    size_t at_ = 0;
};

uint64_t checksum(const uint8_t* data, size_t size) {
    Fnv1a h;
    h.bytes(data, size);
    return h.digest();
}

// Versions 2 and 3 came before the sampler's two replicates (sampler version 1): they kept each
// pixel's sum of its samples' squares (version 2, 120 bytes a pixel) or of its rounds' sums and
// its round count (version 3, 128 bytes), and no sampler version (a 40-byte header). They are
// read without halves, so the image is the same and the error estimate unknown (infinite), and
// such a film can be shown but not resumed or merged with a newer one: nothing an older glint
// rendered is lost by an upgrade. Version 4 is version 5 without the flags (so without AOVs)
// and without the light paths (Film::light_paths, which only adaptive sampling counts: read as 0).
constexpr uint32_t kPerSampleVersion = 2, kRoundVersion = 3, kHalvesVersion = 4, kOldSamplerVersion = 1;
constexpr size_t kOldHeader = 40, kHalvesHeader = 44, kPerSamplePixel = 120;

size_t pixel_size(uint32_t version) {
    if (version == kVersion || version == kHalvesVersion || version == kRoundVersion) return kPixel;
    if (version == kPerSampleVersion) return kPerSamplePixel;
    throw PartialError("unsupported partial file version " + std::to_string(version));
}

size_t header_size(uint32_t version) {
    return version == kVersion ? kHeader : version == kHalvesVersion ? kHalvesHeader : kOldHeader;
}

void put_aov(Writer& w, const Aov& a) {
    for (int c = 0; c < 3; ++c) w.put(a.albedo[c]);
    for (int c = 0; c < 3; ++c) w.put(a.normal[c]);
    w.put(a.depth);
}

Aov get_aov(Reader& r) {
    Aov a;
    for (int c = 0; c < 3; ++c) a.albedo[c] = r.get<double>();
    for (int c = 0; c < 3; ++c) a.normal[c] = r.get<double>();
    a.depth = r.get<double>();
    return a;
}

void put_pixel(Writer& w, const PixelSums& px) {
    for (int c = 0; c < 3; ++c) w.put(px.sum[c]);
    for (int c = 0; c < 3; ++c) w.put(px.half_sum[c]);
    w.put(px.count);
    w.put(px.half_count);
    w.put(px.dropped);
    for (int c = 0; c < 3; ++c) w.put(px.splat[size_t(c)]);
    for (int c = 0; c < 3; ++c) w.put(px.splat_sq[size_t(c)]);
    w.put(px.splats_dropped);
}

void get_pixel(Reader& r, uint32_t version, PixelSums& px) {
    for (int c = 0; c < 3; ++c) px.sum[c] = r.get<double>();
    Rgb second;  // the first half's sums; in older versions, sums of squares
    for (int c = 0; c < 3; ++c) second[c] = r.get<double>();
    px.count = r.get<uint64_t>();
    const uint64_t fourth = version == kPerSampleVersion ? 0 : r.get<uint64_t>();  // half's or rounds' count
    if (version >= kHalvesVersion) {
        px.half_sum = second;
        px.half_count = fourth;
    }
    px.dropped = r.get<uint64_t>();
    for (int c = 0; c < 3; ++c) px.splat[size_t(c)] = r.get<int64_t>();
    for (int c = 0; c < 3; ++c) px.splat_sq[size_t(c)] = r.get<int64_t>();
    px.splats_dropped = r.get<uint64_t>();
}

// The image's size, from the header, checked against the file's size.
void check_size(size_t file_size, size_t header, size_t pixel_bytes, uint32_t width, uint32_t height) {
    // Divides rather than multiplies: 64·W·H overflows 64 bits for W = H = 2^31.
    const size_t body = file_size - header - kTrailer, pixels = body / pixel_bytes;
    if (width == 0 || height == 0 || width > uint32_t(INT32_MAX) || body % pixel_bytes != 0 || pixels % width != 0 ||
        pixels / width != height)
        throw PartialError("size does not match the header");
}

std::string range(const Partial& p) {
    return "[" + std::to_string(p.first_sample) + ", " + std::to_string(p.end_sample) + ")";
}

}  // namespace

Partial partial_of(const RenderJob& render, uint64_t fingerprint, uint32_t spp_done) {
    Partial p;
    p.fingerprint = fingerprint;
    p.first_sample = render.settings().first_sample;
    p.end_sample = render.settings().first_sample + spp_done;
    p.encoding = render.settings().encoding;
    p.film = render.film();
    return p;
}

std::vector<uint8_t> encode_partial(const Partial& p) {
    Writer w;
    const bool aovs = p.film.has_aovs();
    w.bytes.reserve(partial_file_size(p.film.width(), p.film.height(), aovs));
    w.bytes.insert(w.bytes.end(), kMagic, kMagic + 8);
    w.put(kVersion);
    w.put(uint32_t(p.film.width()));
    w.put(uint32_t(p.film.height()));
    w.put(p.first_sample);
    w.put(p.end_sample);
    w.put(uint32_t(p.encoding == Encoding::srgb ? 1 : 0));
    w.put(p.sampler_version);
    w.put(p.fingerprint);
    w.put(aovs ? kHasAovs : 0u);
    w.put(p.film.light_paths());
    for (const PixelSums& px : p.film.pixels()) put_pixel(w, px);
    for (const AovSums& a : p.film.aovs()) {
        put_aov(w, a.sum);
        put_aov(w, a.half_sum);
    }
    w.put(checksum(w.bytes.data(), w.bytes.size()));
    return std::move(w.bytes);
}

uint64_t partial_file_size(int width, int height, bool aovs) {
    return kHeader + (kPixel + (aovs ? kAovPixel : 0)) * uint64_t(width) * uint64_t(height) + kTrailer;
}

Partial decode_partial(const std::vector<uint8_t>& bytes) {
    if (bytes.size() < kOldHeader + kTrailer || std::memcmp(bytes.data(), kMagic, 8) != 0)
        throw PartialError("not a glint partial file");
    uint64_t stored;
    std::memcpy(&stored, &bytes[bytes.size() - kTrailer], kTrailer);
    if (stored != checksum(bytes.data(), bytes.size() - kTrailer))
        throw PartialError("checksum mismatch: the file is corrupt or truncated");
    Reader r(bytes);
    r.get<uint64_t>();  // magic
    const auto version = r.get<uint32_t>();
    const size_t header = header_size(version);
    size_t pixel_bytes = pixel_size(version);
    if (bytes.size() < header + kTrailer) throw PartialError("size does not match the header");
    const auto width = r.get<uint32_t>(), height = r.get<uint32_t>();
    Partial p;
    p.first_sample = r.get<uint32_t>();
    p.end_sample = r.get<uint32_t>();
    if (p.end_sample <= p.first_sample) throw PartialError("empty or reversed sample range");
    const auto encoding = r.get<uint32_t>();
    if (encoding > 1) throw PartialError("unknown PNG encoding " + std::to_string(encoding) + " (0 gamma 2.2, 1 sRGB)");
    p.encoding = encoding == 1 ? Encoding::srgb : Encoding::gamma22;
    p.sampler_version = version >= kHalvesVersion ? r.get<uint32_t>() : kOldSamplerVersion;
    p.fingerprint = r.get<uint64_t>();
    const uint32_t flags = version == kVersion ? r.get<uint32_t>() : 0;
    const uint64_t light_paths = version == kVersion ? r.get<uint64_t>() : 0;
    if ((flags & ~kHasAovs) != 0) throw PartialError("unknown flags " + std::to_string(flags));
    if (flags & kHasAovs) pixel_bytes += kAovPixel;
    check_size(bytes.size(), header, pixel_bytes, width, height);
    p.film = Film(int(width), int(height), (flags & kHasAovs) != 0);
    p.film.set_light_paths(light_paths);
    for (PixelSums& px : p.film.pixels()) get_pixel(r, version, px);
    for (AovSums& a : p.film.aovs()) {
        a.sum = get_aov(r);
        a.half_sum = get_aov(r);
    }
    return p;
}

void check_continues(const Partial& checkpoint, uint64_t fingerprint, const RenderSettings& settings) {
    if (checkpoint.fingerprint != fingerprint)
        throw std::invalid_argument("it is from another scene or settings (fingerprint differs)");
    if (checkpoint.sampler_version != kSamplerVersion)
        throw std::invalid_argument("it was rendered by another version of glint's sampler (" +
                                    std::to_string(checkpoint.sampler_version) + ", not " +
                                    std::to_string(kSamplerVersion) + ")");
    if (checkpoint.encoding != settings.encoding) throw std::invalid_argument("its PNG encoding differs from the job's");
    if (checkpoint.first_sample != settings.first_sample)
        throw std::invalid_argument("it starts at sample " + std::to_string(checkpoint.first_sample) + ", the job at " +
                                    std::to_string(settings.first_sample));
}

Partial merge_partials(std::vector<Partial> parts) {
    if (parts.empty()) throw PartialError("no parts to merge");
    std::sort(parts.begin(), parts.end(), [](const Partial& a, const Partial& b) { return a.first_sample < b.first_sample; });
    Partial merged = std::move(parts.front());
    for (size_t i = 1; i < parts.size(); ++i) {
        const Partial& p = parts[i];
        if (p.fingerprint != merged.fingerprint) throw PartialError("part " + range(p) + " is from another scene or settings");
        if (p.sampler_version != merged.sampler_version)
            throw PartialError("part " + range(p) + " was rendered by another version of glint's sampler (" +
                               std::to_string(p.sampler_version) + ", not " + std::to_string(merged.sampler_version) + ")");
        if (p.film.width() != merged.film.width() || p.film.height() != merged.film.height())
            throw PartialError("part " + range(p) + " has another image size");
        if (p.first_sample < merged.end_sample)
            throw PartialError("parts overlap: " + range(parts[i - 1]) + " and " + range(p));
        if (p.first_sample > merged.end_sample)
            throw PartialError("samples [" + std::to_string(merged.end_sample) + ", " + std::to_string(p.first_sample) +
                               ") are missing");
        merged.film.merge(p.film);
        merged.end_sample = p.end_sample;
    }
    return merged;
}

}  // namespace glint
