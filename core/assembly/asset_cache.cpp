#include "assembly/asset_cache.h"

#include <system_error>

namespace glint {

Asset AssetCache::get(AssetKind kind, const std::filesystem::path& file, const std::function<Asset()>& make) {
    std::error_code size_error, time_error;
    const uintmax_t size = std::filesystem::file_size(file, size_error);
    const auto modified = std::filesystem::last_write_time(file, time_error);
    if (size_error || time_error) return make();
    const Key key{kind, file.string(), size, modified};
    {
        const std::lock_guard lock(mutex_);
        if (const auto found = entries_.find(key); found != entries_.end()) {
            recency_.splice(recency_.begin(), recency_, found->second.used);
            return found->second.asset;
        }
    }
    Asset made = make();
    const std::lock_guard lock(mutex_);
    if (const auto found = entries_.find(key); found != entries_.end()) return found->second.asset;
    keep(key, made);
    return made;
}

void AssetCache::keep(const Key& key, const Asset& asset) {
    if (asset.bytes > max_bytes_) return;
    while (bytes_ + asset.bytes > max_bytes_) {
        const auto oldest = entries_.find(recency_.back());
        bytes_ -= oldest->second.asset.bytes;
        entries_.erase(oldest);
        recency_.pop_back();
    }
    recency_.push_front(key);
    entries_.emplace(key, Entry{asset, recency_.begin()});
    bytes_ += asset.bytes;
}

size_t AssetCache::bytes() const {
    const std::lock_guard lock(mutex_);
    return bytes_;
}

size_t AssetCache::entries() const {
    const std::lock_guard lock(mutex_);
    return entries_.size();
}

}  // namespace glint
