// A 64-bit fingerprint of everything that decides an image's pixels (geometry, materials,
// camera, integrator, size, filter, seed), so parts rendered on different machines can be
// checked to belong to the same job before they are merged.
#pragma once

#include <cstdint>
#include <cstring>
#include <string_view>

#include "render/settings.h"
#include "scene/scene.h"

namespace glint {

// FNV-1a, 64-bit: simple, fast, and enough to tell jobs apart (not a cryptographic hash).
class Fnv1a {
public:
    void bytes(const void* data, size_t size) {
        const auto* p = static_cast<const uint8_t*>(data);
        for (size_t i = 0; i < size; ++i) hash_ = (hash_ ^ p[i]) * 0x100000001B3ull;
    }
    template <typename T>
    void value(const T& v) {
        bytes(&v, sizeof v);
    }
    void vec(const Vec3& v) {
        value(v.x);
        value(v.y);
        value(v.z);
    }
    uint64_t digest() const { return hash_; }

private:
    uint64_t hash_ = 0xCBF29CE484222325ull;
};

// Covers the settings that decide pixel values; not spp or first_sample (parts differ in those),
// nor target error, time limit or PNG encoding.
uint64_t fingerprint(const Scene& scene, const RenderSettings& settings);

}  // namespace glint
