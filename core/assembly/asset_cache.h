// Decoded texture files, and the environment maps built from them, kept between scene loads: a
// service that renders many jobs of one scene decodes each file, and builds an environment's
// sampling distribution, once rather than once per job. An entry is keyed by its kind and the
// file's resolved path, size and modification time, so an edited file is read again. The cache
// holds at most its byte budget, dropping the least recently used entries first (a scene that
// holds one keeps it alive). Thread-safe; two loads of one file at once may both decode it.
#pragma once

#include <cstddef>
#include <filesystem>
#include <functional>
#include <list>
#include <map>
#include <memory>
#include <mutex>
#include <string>

namespace glint {

enum class AssetKind { texture, environment };

struct Asset {
    std::shared_ptr<const void> value;  // a Texture or an EnvironmentMap, by kind
    int width = 0, height = 0;          // of the file's image
    size_t negative_values = 0;         // float values below 0 that decoding set to 0
    size_t bytes = 0;                   // the memory `value` holds
};

class AssetCache {
public:
    // 1 GiB: a few 4096 × 2048 environments and their distributions, or dozens of textures.
    static constexpr size_t kDefaultBytes = size_t(1) << 30;
    explicit AssetCache(size_t max_bytes = kDefaultBytes) : max_bytes_(max_bytes) {}

    // The asset of `kind` made from `file`: the one kept from an earlier call if the file's size
    // and modification time are unchanged, else make()'s (whose exceptions pass through, nothing
    // kept). A file that cannot be examined is made and not kept.
    Asset get(AssetKind kind, const std::filesystem::path& file, const std::function<Asset()>& make);

    size_t bytes() const;
    size_t entries() const;

private:
    struct Key {
        AssetKind kind;
        std::string path;
        uintmax_t size;
        std::filesystem::file_time_type modified;
        auto operator<=>(const Key&) const = default;
    };
    using Recency = std::list<Key>;  // most recently used first
    struct Entry {
        Asset asset;
        Recency::iterator used;
    };
    void keep(const Key& key, const Asset& asset);  // with the lock held

    const size_t max_bytes_;
    mutable std::mutex mutex_;
    std::map<Key, Entry> entries_;
    Recency recency_;
    size_t bytes_ = 0;
};

}  // namespace glint
