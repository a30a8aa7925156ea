#include "io/texture_file.h"

#include <stb_image.h>

#include <algorithm>
#include <climits>
#include <cmath>
#include <cstring>
#include <iterator>
#include <memory>

#include <OpenEXR/Iex.h>
#include <OpenEXR/ImfChannelList.h>
#include <OpenEXR/ImfFrameBuffer.h>
#include <OpenEXR/ImfHeader.h>
#include <OpenEXR/ImfIO.h>
#include <OpenEXR/ImfInputFile.h>

namespace glint {
namespace {

[[noreturn]] void fail(const std::string& name, const std::string& what) {
    throw TextureError("texture '" + name + "' " + what);
}

// A NaN or infinity would spread through every path that meets it, so it is refused; negative
// values (lossy EXR compression undershoots near black) become 0 and are counted.
size_t clean_floats(std::vector<float>& values, const std::string& name) {
    size_t negative = 0;
    for (float& v : values) {
        if (!std::isfinite(v)) fail(name, "holds a NaN or infinite texel");
        if (v < 0) {
            v = 0;
            ++negative;
        }
    }
    return negative;
}

// ---- stb_image: every format but OpenEXR ----

struct StbFree {
    void operator()(void* p) const { stbi_image_free(p); }
};

std::string stb_reason() {
    const char* reason = stbi_failure_reason();
    return reason ? reason : "no reason given";
}

// stb's loader `load` (8-bit or float), asked for the file's own channels; the size must be
// the one its header declared, which the caller has checked.
template <typename T, typename Load>
std::vector<T> stb_texels(Load load, const std::vector<uint8_t>& bytes, const std::string& name, int width,
                          int height, int& channels) {
    int w = 0, h = 0;
    const std::unique_ptr<T, StbFree> texels(load(bytes.data(), int(bytes.size()), &w, &h, &channels, 0));
    if (!texels) fail(name, "is corrupt or truncated (" + stb_reason() + ")");
    if (w != width || h != height || channels < 1 || channels > 4)
        fail(name, "is corrupt (its header and its image disagree on the size)");
    return std::vector<T>(texels.get(), texels.get() + size_t(w) * size_t(h) * size_t(channels));
}

DecodedTexture decode_stb(const std::vector<uint8_t>& bytes, const std::string& name, const TextureLimits& limits) {
    if (bytes.size() > size_t(INT_MAX)) fail(name, "is larger than the 2 GiB an image file may be");
    int width = 0, height = 0, channels = 0;
    if (!stbi_info_from_memory(bytes.data(), int(bytes.size()), &width, &height, &channels))
        fail(name, "is not an image glint reads (" + stb_reason() + ")");
    check_texture_size(name, width, height, limits);
    if (stbi_is_hdr_from_memory(bytes.data(), int(bytes.size()))) {
        std::vector<float> texels = stb_texels<float>(stbi_loadf_from_memory, bytes, name, width, height, channels);
        const size_t negative = clean_floats(texels, name);
        return {Texture::from_floats(width, height, channels, std::move(texels)), negative};
    }
    // stbi_load gives 16-bit PNGs and PNMs rounded to 8 bits.
    std::vector<uint8_t> texels = stb_texels<uint8_t>(stbi_load_from_memory, bytes, name, width, height, channels);
    return {Texture::from_bytes(width, height, channels, std::move(texels)), 0};
}

// ---- OpenEXR ----

constexpr uint8_t kExrMagic[4] = {0x76, 0x2f, 0x31, 0x01};
constexpr uint32_t kTiledFlag = 0x200, kDeepFlag = 0x800, kMultipartFlag = 0x1000;

// OpenEXR reads from a stream; this one reads the file's bytes, already in memory.
class MemoryInput final : public Imf::IStream {
public:
    explicit MemoryInput(const std::vector<uint8_t>& bytes) : Imf::IStream("memory"), bytes_(bytes) {}
    bool read(char c[], int n) override {
        if (n < 0 || at_ > bytes_.size() || size_t(n) > bytes_.size() - at_) throw Iex::InputExc("the file ends early");
        std::memcpy(c, bytes_.data() + at_, size_t(n));
        at_ += size_t(n);
        return at_ < bytes_.size();
    }
    uint64_t tellg() override { return at_; }
    void seekg(uint64_t pos) override { at_ = pos; }

private:
    const std::vector<uint8_t>& bytes_;
    uint64_t at_ = 0;
};

// Bounds-checked reads of a header's little-endian fields and NUL-terminated names.
class HeaderCursor {
public:
    HeaderCursor(const uint8_t* data, size_t size, const std::string& name) : data_(data), size_(size), name_(name) {}
    const uint8_t* take(size_t n) {
        if (n > size_ - at_) fail(name_, "is a truncated or corrupt OpenEXR file (its header)");
        at_ += n;
        return data_ + at_ - n;
    }
    HeaderCursor part(size_t n) { return HeaderCursor(take(n), n, name_); }
    uint8_t u8() { return *take(1); }
    uint32_t u32() {
        const uint8_t* p = take(4);
        return uint32_t(p[0]) | uint32_t(p[1]) << 8 | uint32_t(p[2]) << 16 | uint32_t(p[3]) << 24;
    }
    int32_t i32() { return int32_t(u32()); }
    std::string text() {  // OpenEXR's names are at most 255 bytes
        const size_t most = std::min(size_ - at_, size_t(256));
        const auto* end = static_cast<const uint8_t*>(std::memchr(data_ + at_, 0, most));
        const size_t length = end ? size_t(end - (data_ + at_)) : size_ - at_ + 1;  // none: fail in take
        const auto* start = reinterpret_cast<const char*>(take(length + 1));
        return std::string(start, length);
    }

private:
    const uint8_t* data_;
    size_t size_, at_ = 0;
    const std::string& name_;
};

// What OpenEXR's reader will set aside, from the file's (first) header. OpenEXR allocates what a
// header declares (attribute values, a table entry per row, a chunk of rows of every channel)
// before it finds that the file holds less, so the header is read here first and bounded.
struct ExrLayout {
    int64_t width = 0, height = 0;
    double texel_bytes = 0;  // every channel in the file together
    int chunk_rows = 1;      // rows compressed together, by compression method
    uint32_t tile_width = 0, tile_height = 0;
};

int chunk_rows(uint8_t compression) {
    // NONE, RLE, ZIPS, ZIP, PIZ, PXR24, B44, B44A, DWAA, DWAB; OpenEXR refuses others.
    constexpr int kRows[] = {1, 1, 1, 16, 32, 16, 32, 32, 32, 256};
    return compression < std::size(kRows) ? kRows[compression] : 256;
}

double channel_bytes(HeaderCursor list) {
    double bytes = 0;
    while (!list.text().empty()) {
        const uint32_t type = list.u32();  // 0 UINT, 1 HALF, 2 FLOAT
        list.take(12);                     // linear flag, reserved, x and y sampling
        bytes += type == 1 ? 2 : 4;
    }
    return bytes;
}

void read_attribute(const std::string& attribute, const std::string& type, HeaderCursor value, ExrLayout& layout) {
    if (attribute == "dataWindow" && type == "box2i") {
        const int64_t x0 = value.i32(), y0 = value.i32(), x1 = value.i32(), y1 = value.i32();
        layout.width = x1 - x0 + 1;
        layout.height = y1 - y0 + 1;
    } else if (attribute == "channels" && type == "chlist") {
        layout.texel_bytes += channel_bytes(value);  // OpenEXR adds a repeated list's channels to the first's
    } else if (attribute == "compression" && type == "compression") {
        layout.chunk_rows = chunk_rows(value.u8());
    } else if (attribute == "tiles" && type == "tiledesc") {
        layout.tile_width = value.u32();
        layout.tile_height = value.u32();
    }
}

ExrLayout scan_exr_header(const std::vector<uint8_t>& bytes, const std::string& name) {
    HeaderCursor in(bytes.data(), bytes.size(), name);
    in.take(sizeof kExrMagic);
    const uint32_t version = in.u32();
    if (version & (kDeepFlag | kMultipartFlag))
        fail(name, "is a deep or multi-part OpenEXR file (a texture is one flat image)");
    ExrLayout layout;
    for (std::string attribute = in.text(); !attribute.empty(); attribute = in.text()) {
        const std::string type = in.text();
        const uint32_t size = in.u32();
        read_attribute(attribute, type, in.part(size), layout);
    }
    if (layout.width < 1 || layout.height < 1)
        fail(name, "is a corrupt OpenEXR file (no data window, or an empty one)");
    if (!(version & kTiledFlag)) layout.tile_width = layout.tile_height = 0;
    return layout;
}

// Roughly what OpenEXR allocates before it reads a texel: for scanlines, a chunk of rows of every
// channel and three tables of one entry per row; for tiles, a tile of every channel, a row of
// tiles of the (at most four float) channels read, and the offsets of every tile of every level
// (all levels together have at most four times the first's tiles).
double reader_bytes(const ExrLayout& layout) {
    const double width = double(layout.width), height = double(layout.height);
    double bytes = width * layout.texel_bytes * layout.chunk_rows + 24 * height;
    if (layout.tile_width > 0 && layout.tile_height > 0) {
        const double tiles = std::ceil(width / layout.tile_width) * std::ceil(height / layout.tile_height);
        bytes = std::max(bytes, double(layout.tile_width) * layout.tile_height * layout.texel_bytes +
                                    width * layout.tile_height * 16 + 32 * tiles);
    }
    return bytes;
}

// The reader may take as much as the largest texture the limit admits (float RGBA), and never
// less than 64 MiB, so a small limit does not refuse small files over their layout.
void check_reader_memory(const ExrLayout& layout, const std::string& name, const TextureLimits& limits) {
    const double allowed = std::max(16.0 * double(limits.max_texels_per_file), 64.0 * (1 << 20));
    if (reader_bytes(layout) > allowed)
        fail(name, "is an OpenEXR file laid out (in channels, rows a chunk or tiles) to need more memory to read "
                   "than the texel limit allows");
}

// The channels a texture takes: R, G, B (colour; a missing one reads as 0) or else Y (grey),
// and A if there is one.
std::vector<std::string> texture_channels(const Imf::ChannelList& list, const std::string& name) {
    const bool colour = list.findChannel("R") || list.findChannel("G") || list.findChannel("B");
    if (!colour && !list.findChannel("Y")) fail(name, "has none of the OpenEXR channels R, G, B or Y");
    std::vector<std::string> channels{"Y"};
    if (colour) channels = {"R", "G", "B"};
    if (list.findChannel("A")) channels.push_back("A");
    for (const std::string& c : channels) {
        const Imf::Channel* channel = list.findChannel(c);
        if (channel && (channel->xSampling != 1 || channel->ySampling != 1))
            fail(name, "has a subsampled channel " + c + " (textures take full-resolution channels)");
    }
    return channels;
}

DecodedTexture read_exr(Imf::InputFile& file, const ExrLayout& layout, const std::string& name) {
    const Imath::Box2i window = file.header().dataWindow();
    if (int64_t(window.max.x) - window.min.x + 1 != layout.width ||
        int64_t(window.max.y) - window.min.y + 1 != layout.height)
        fail(name, "is a corrupt OpenEXR file (two data windows)");
    const std::vector<std::string> channels = texture_channels(file.header().channels(), name);
    const size_t count = channels.size(), row = size_t(layout.width) * count;
    std::vector<float> texels(row * size_t(layout.height));
    Imf::FrameBuffer frame;
    for (size_t c = 0; c < count; ++c)
        frame.insert(channels[c],
                     Imf::Slice::Make(Imf::FLOAT, texels.data() + c, window, sizeof(float) * count, sizeof(float) * row));
    file.setFrameBuffer(frame);
    file.readPixels(window.min.y, window.max.y);  // rows in increasing y: top first
    const size_t negative = clean_floats(texels, name);
    return {Texture::from_floats(int(layout.width), int(layout.height), int(count), std::move(texels)), negative};
}

DecodedTexture decode_exr(const std::vector<uint8_t>& bytes, const std::string& name, const TextureLimits& limits) {
    const ExrLayout layout = scan_exr_header(bytes, name);
    check_texture_size(name, layout.width, layout.height, limits);
    check_reader_memory(layout, name, limits);
    try {
        MemoryInput stream(bytes);
        Imf::InputFile file(stream);
        return read_exr(file, layout, name);
    } catch (const TextureError&) {
        throw;
    } catch (const std::exception& e) {  // OpenEXR's Iex exceptions, and its allocations'
        fail(name, std::string("is a corrupt or truncated OpenEXR file (") + e.what() + ")");
    }
}

}  // namespace

// Called with the header's size, before the texels are allocated.
void check_texture_size(const std::string& name, int64_t width, int64_t height, const TextureLimits& limits) {
    if (width < 1 || height < 1) fail(name, "has no texels");
    if (width > INT_MAX || height > INT_MAX || uint64_t(width) * uint64_t(height) > limits.max_texels_per_file)
        fail(name, "is " + std::to_string(width) + "x" + std::to_string(height) + " texels, more than the " +
                       std::to_string(limits.max_texels_per_file) + " a texture may have");
}

DecodedTexture decode_texture(const std::vector<uint8_t>& bytes, const std::string& name, const TextureLimits& limits) {
    if (bytes.empty()) fail(name, "is empty");
    if (bytes.size() >= sizeof kExrMagic && std::equal(std::begin(kExrMagic), std::end(kExrMagic), bytes.begin()))
        return decode_exr(bytes, name, limits);
    return decode_stb(bytes, name, limits);
}

}  // namespace glint
