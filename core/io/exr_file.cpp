#include "io/exr_file.h"

#include <cstring>
#include <set>
#include <stdexcept>

#include <OpenEXR/ImfChannelList.h>
#include <OpenEXR/ImfFrameBuffer.h>
#include <OpenEXR/ImfHeader.h>
#include <OpenEXR/ImfIO.h>
#include <OpenEXR/ImfOutputFile.h>

namespace glint {
namespace {

// OpenEXR writes to a stream it may seek back in (to fill in the line offset table).
class MemoryStream : public Imf::OStream {
public:
    MemoryStream() : Imf::OStream("memory") {}
    void write(const char c[], int n) override {
        if (at_ + size_t(n) > bytes.size()) bytes.resize(at_ + size_t(n));
        std::memcpy(bytes.data() + at_, c, size_t(n));
        at_ += size_t(n);
    }
    uint64_t tellp() override { return at_; }
    void seekp(uint64_t pos) override { at_ = pos; }
    std::vector<uint8_t> bytes;

private:
    uint64_t at_ = 0;
};

std::string channel_name(const ExrLayer& layer, size_t c) {
    return layer.name.empty() ? layer.channels[c] : layer.name + "." + layer.channels[c];
}

// Throws unless every plane fits the image and every name is new.
void check_layers(size_t pixels, const std::vector<ExrLayer>& layers) {
    std::set<std::string> names;
    for (const ExrLayer& layer : layers) {
        if (layer.planes.size() != layer.channels.size())
            throw std::invalid_argument("EXR layer '" + layer.name + "' has a plane count unlike its channels'");
        for (size_t c = 0; c < layer.channels.size(); ++c) {
            if (layer.planes[c].size() != pixels)
                throw std::invalid_argument("EXR channel " + channel_name(layer, c) + " is not one value a pixel");
            if (!names.insert(channel_name(layer, c)).second)
                throw std::invalid_argument("EXR channel " + channel_name(layer, c) + " given twice");
        }
    }
}

}  // namespace

ExrLayer exr_layer(std::string name, const Image& image, std::vector<std::string> channels) {
    ExrLayer layer{std::move(name), std::move(channels), {}};
    const size_t pixels = size_t(image.width) * size_t(image.height);
    layer.planes.assign(layer.channels.size(), std::vector<float>(pixels));
    for (size_t i = 0; i < pixels; ++i)
        for (size_t c = 0; c < layer.channels.size(); ++c) layer.planes[c][i] = image.rgb[i * 3 + c];
    return layer;
}

std::vector<uint8_t> encode_exr(int width, int height, const std::vector<ExrLayer>& layers) {
    check_layers(size_t(width) * size_t(height), layers);
    Imf::Header header(width, height);  // ZIP compression, rows in increasing y: top first
    Imf::FrameBuffer frame;
    for (const ExrLayer& layer : layers)
        for (size_t c = 0; c < layer.channels.size(); ++c) {
            const std::string name = channel_name(layer, c);
            header.channels().insert(name, Imf::Channel(Imf::FLOAT));
            // OpenEXR only reads the planes while writing, through a pointer it wants non-const.
            char* base = reinterpret_cast<char*>(const_cast<float*>(layer.planes[c].data()));
            frame.insert(name, Imf::Slice(Imf::FLOAT, base, sizeof(float), sizeof(float) * size_t(width)));
        }
    MemoryStream stream;
    try {
        Imf::OutputFile file(stream, header);
        file.setFrameBuffer(frame);
        file.writePixels(height);
    } catch (const std::exception& e) {
        throw std::runtime_error(std::string("cannot write the EXR file: ") + e.what());
    }
    return std::move(stream.bytes);
}

}  // namespace glint
