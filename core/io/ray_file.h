// The binary ray and hit files of ../shared/rays/FORMAT.md, for comparing BVHs on identical rays.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace glint {

struct RayRecord {
    float o[3], tmin, d[3], tmax;
};
struct HitRecord {
    float t;
    uint32_t prim;  // 0xFFFFFFFF for a miss
};
static_assert(sizeof(RayRecord) == 32 && sizeof(HitRecord) == 8);

std::vector<RayRecord> read_rays(const std::string& path);  // throws FileError
void write_hits(const std::string& path, const std::vector<HitRecord>& hits);
std::vector<HitRecord> read_hits(const std::string& path);

}  // namespace glint
