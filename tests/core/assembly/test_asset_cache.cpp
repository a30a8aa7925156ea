// The cache of decoded files: a file is made once while it is unchanged, made again once it
// changes, entries beyond the byte budget go least recently used first, and what fails to be
// made is not kept. Through the loader: two scenes of one environment share its map, and each
// still gets the file's warning.
#include <gtest/gtest.h>

#include <memory>
#include <stdexcept>

#include "assembly/asset_cache.h"
#include "assembly/scene_loader.h"
#include "support/image_files.h"
#include "support/scene_folder.h"

namespace glint {
namespace {

class AssetCacheTest : public testing::SceneFolderTest {
protected:
    AssetCacheTest() : SceneFolderTest("glint-asset-cache") {}
    // The asset of `file` through `cache`, counting the times it is made; each is `bytes` large.
    Asset get(AssetCache& cache, const std::string& file, size_t bytes = 10) {
        return cache.get(AssetKind::texture, folder_.path() / file, [&] {
            ++made_;
            return Asset{std::make_shared<const int>(made_), 1, 1, 0, bytes};
        });
    }
    int made_ = 0;
};

TEST_F(AssetCacheTest, AnUnchangedFileIsMadeOnce) {
    folder_.write("a.png", {1, 2, 3});
    AssetCache cache;
    const Asset first = get(cache, "a.png"), second = get(cache, "a.png");
    EXPECT_EQ(made_, 1);
    EXPECT_EQ(first.value, second.value);
    EXPECT_EQ(cache.entries(), 1u);
    EXPECT_EQ(cache.bytes(), 10u);
    // Another kind of asset from the same file is another entry.
    cache.get(AssetKind::environment, folder_.path() / "a.png", [] { return Asset{std::make_shared<const int>(0), 1, 1, 0, 5}; });
    EXPECT_EQ(cache.entries(), 2u);
}

TEST_F(AssetCacheTest, AChangedFileIsMadeAgain) {
    folder_.write("a.png", {1, 2, 3});
    AssetCache cache;
    get(cache, "a.png");
    folder_.write("a.png", {1, 2, 3, 4});
    get(cache, "a.png");
    EXPECT_EQ(made_, 2);
}

TEST_F(AssetCacheTest, TheLeastRecentlyUsedGoFirstBeyondTheBudget) {
    for (const char* name : {"a.png", "b.png", "c.png"}) folder_.write(name, {1});
    AssetCache cache(25);
    get(cache, "a.png");
    get(cache, "b.png");
    get(cache, "a.png");  // a is now the more recent
    get(cache, "c.png");  // 30 bytes: b goes
    EXPECT_EQ(cache.bytes(), 20u);
    EXPECT_EQ(made_, 3);
    get(cache, "a.png");
    EXPECT_EQ(made_, 3);
    get(cache, "b.png");
    EXPECT_EQ(made_, 4);
    // One larger than the whole budget is made and handed out, not kept.
    folder_.write("huge.png", {1});
    EXPECT_NE(get(cache, "huge.png", 26).value, nullptr);
    EXPECT_EQ(cache.bytes(), 20u);
}

TEST_F(AssetCacheTest, WhatFailsIsNotKept) {
    folder_.write("a.png", {1});
    AssetCache cache;
    EXPECT_THROW(cache.get(AssetKind::texture, folder_.path() / "a.png", []() -> Asset { throw std::runtime_error("bad"); }),
                 std::runtime_error);
    EXPECT_EQ(cache.entries(), 0u);
    // A file that is not there cannot be keyed: made every time.
    get(cache, "missing.png");
    get(cache, "missing.png");
    EXPECT_EQ(made_, 2);
}

TEST_F(AssetCacheTest, ScenesOfOneEnvironmentShareItsMapAndEachGetsItsWarning) {
    folder_.write("sky.exr", testing::exr(4, 2, {"Y"}, {{-0.5f, 1, 1, 1, 1, 1, 1, 1}}));
    AssetCache cache;
    const std::string text = R"({"environment": {"file": "sky.exr", "rotation": 30}})";
    const LoadedScene a = parse_scene(text, folder_.path(), {}, &cache);
    const LoadedScene b = parse_scene(R"({"environment": {"file": "sky.exr", "strength": 2}})", folder_.path(), {}, &cache);
    EXPECT_EQ(&a.scene->environment()->map(), &b.scene->environment()->map());
    EXPECT_EQ(b.scene->environment()->settings().strength, 2);
    ASSERT_EQ(b.warnings.size(), 1u);
    EXPECT_NE(b.warnings[0].find("1 negative values in sky.exr set to 0"), std::string::npos) << b.warnings[0];
    // The scene's texel limit counts it on every load.
    SceneLimits small;
    small.max_texels = 7;
    EXPECT_THROW(parse_scene(text, folder_.path(), small, &cache), SceneError);
}

}  // namespace
}  // namespace glint
