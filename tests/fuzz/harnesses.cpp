#include "harnesses.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <limits>
#include <string>
#include <vector>

#include <httplib.h>

#include "assembly/fingerprint.h"
#include "assembly/partial_file.h"
#include "assembly/scene_loader.h"
#include "http/auth.h"
#include "http/job_patch.h"
#include "http/job_request.h"
#include "io/obj_loader.h"
#include "io/texture_file.h"
#include "service/priority.h"
#include "service/service_config.h"

namespace glint::fuzz {
namespace {

std::string text(const uint8_t* data, size_t size) { return std::string(reinterpret_cast<const char*>(data), size); }

// A broken property is a finding like a crash; abort so libFuzzer keeps the input.
void require(bool property) {
    if (!property) std::abort();
}

// One request read from memory instead of a socket; what the server writes back is dropped.
class MemoryStream final : public httplib::Stream {
public:
    explicit MemoryStream(std::string request) : request_(std::move(request)) {}
    bool is_readable() const override { return true; }
    bool is_writable() const override { return true; }
    ssize_t read(char* ptr, size_t size) override {
        const size_t n = std::min(size, request_.size() - read_);
        std::memcpy(ptr, request_.data() + read_, n);
        read_ += n;
        return ssize_t(n);
    }
    ssize_t write(const char*, size_t size) override { return ssize_t(size); }
    void get_remote_ip_and_port(std::string& ip, int& port) const override { loopback(ip, port); }
    void get_local_ip_and_port(std::string& ip, int& port) const override { loopback(ip, port); }
    socket_t socket() const override { return INVALID_SOCKET; }

private:
    static void loopback(std::string& ip, int& port) {
        ip = "127.0.0.1";
        port = 8080;
    }
    std::string request_;
    size_t read_ = 0;
};

// cpp-httplib's server with no routes, whose token check is the API's: process_request() is
// what GuardedServer runs for each request, so the target goes through the same request-line
// split, path decoding and parse_query_text as a real request's.
class TokenServer final : public httplib::Server {
public:
    static constexpr const char* kToken = "secret";

    TokenServer() {
        set_pre_routing_handler([](const httplib::Request& req, httplib::Response&) {
            require(check_token(req, kToken).empty() == admissible(req));
            return HandlerResponse::Unhandled;
        });
    }
    void serve(const std::string& request) {
        MemoryStream stream(request);
        bool closed = false;
        process_request(stream, true, closed, nullptr);
    }

private:
    // The property: a job route admits a request only with the exact token, in the header, or
    // in the query where a route allows it and no header is sent.
    static bool admissible(const httplib::Request& req) {
        if (!needs_token(req.path)) return true;
        const std::string header = req.get_header_value("Authorization");
        if (!header.empty()) return header == std::string("Bearer ") + kToken;
        return req.has_param("token") && req.get_param_value("token") == kToken && token_in_query_allowed(req);
    }
};

}  // namespace

std::filesystem::path mesh_folder() { return GLINT_FUZZ_DIR "/corpus/obj"; }
std::filesystem::path scenes_folder() { return GLINT_SCENES_DIR; }

void scene(const uint8_t* data, size_t size) {
    try {
        const LoadedScene loaded = parse_scene(text(data, size), mesh_folder());
        require(loaded.scene != nullptr);
    } catch (const SceneError&) {
    }
}

void obj(const uint8_t* data, size_t size) {
    try {
        const ObjMesh mesh = parse_obj(text(data, size));
        for (const auto& t : mesh.triangles)
            for (const uint32_t v : t) require(v < mesh.vertices.size());
        require(to_triangles(mesh).size() == mesh.triangles.size());
    } catch (const ObjError&) {
    }
}

// The checksum would stop almost every mutation at the first check, so the harness appends the
// right one: the fuzzer explores the header and body checks behind it. A file of the current
// version that decodes must encode to the same bytes (nothing is read leniently); an older one
// is upgraded, and the upgrade must itself encode back byte for byte (found by fuzzing:
// tests/fuzz/regressions/partial/version-two-upgrade.bin, a version 2 file).
void partial(const uint8_t* data, size_t size) {
    std::vector<uint8_t> bytes(data, data + size);
    Fnv1a h;
    h.bytes(bytes.data(), bytes.size());
    const uint64_t sum = h.digest();
    const auto* p = reinterpret_cast<const uint8_t*>(&sum);
    bytes.insert(bytes.end(), p, p + sizeof sum);
    try {
        const std::vector<uint8_t> encoded = encode_partial(decode_partial(bytes));
        constexpr size_t kVersionAt = 8;
        const bool current = encoded.size() >= kVersionAt + 4 && bytes.size() >= kVersionAt + 4 &&
                             std::equal(bytes.begin() + kVersionAt, bytes.begin() + kVersionAt + 4, encoded.begin() + kVersionAt);
        require(current ? encoded == bytes : encode_partial(decode_partial(encoded)) == encoded);
    } catch (const PartialError&) {
    }
}

void job_request(const uint8_t* data, size_t size) {
    try {
        const LoadedScene loaded = parse_job_request(text(data, size), scenes_folder(), ServiceConfig{}.scene).scene;
        require(loaded.scene != nullptr);
    } catch (const ServiceError&) {
    }
}

void query(const uint8_t* data, size_t size) {
    static TokenServer server;
    server.serve("GET " + text(data, size) + " HTTP/1.1\r\nHost: localhost\r\n\r\n");
}

void job_patch(const uint8_t* data, size_t size) {
    try {
        const JobPatch patch = parse_job_patch(text(data, size));
        require(!patch.priority || (*patch.priority >= kMinPriority && *patch.priority <= kMaxPriority));
    } catch (const ServiceError&) {
    }
}

// A lower texel limit than the default: the fuzzer's time goes to the decoders' parsing, not to
// decoding the large images a few bytes can declare (the limit's check is the same code).
void texture(const uint8_t* data, size_t size) {
    try {
        const std::vector<uint8_t> bytes(data, data + size);
        const DecodedTexture decoded = decode_texture(bytes, "fuzz", {.max_texels_per_file = 1 << 20});
        const Texture& t = decoded.texture;
        require(t.width() >= 1 && t.height() >= 1 && t.channels() >= 1 && t.channels() <= 4);
        const double nan = std::numeric_limits<double>::quiet_NaN();
        for (const ColorSpace colorspace : {ColorSpace::srgb, ColorSpace::linear})
            for (int channel = -1; channel < 4; ++channel) {
                const TextureLookup lookup{.texture = &t, .colorspace = colorspace, .channel = channel};
                for (const double u : {0.0, 0.37, -2.6, 1e9, nan}) {
                    const Rgb c = lookup.rgb(u, 1 - u);
                    require(is_finite(c) && min_component(c) >= 0 && std::isfinite(lookup.value(1 - u, u)));
                }
            }
    } catch (const TextureError&) {
    }
}

}  // namespace glint::fuzz
