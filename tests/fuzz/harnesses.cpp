#include "harnesses.h"

#include <algorithm>
#include <cstdlib>
#include <string>
#include <vector>

#include "http/job_request.h"
#include "io/fingerprint.h"
#include "io/obj_loader.h"
#include "io/partial_file.h"
#include "io/scene_loader.h"
#include "service/service_config.h"

namespace glint::fuzz {
namespace {

std::string text(const uint8_t* data, size_t size) { return std::string(reinterpret_cast<const char*>(data), size); }

// A broken property is a finding like a crash; abort so libFuzzer keeps the input.
void require(bool property) {
    if (!property) std::abort();
}

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

}  // namespace glint::fuzz
