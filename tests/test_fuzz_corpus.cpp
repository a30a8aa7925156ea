// Replays the fuzzers' seed corpus and every input they ever crashed on (tests/fuzz/regressions/)
// through the harnesses, in the normal build and under .ci/sanitizers: each must end in the
// parser's own clean error or a valid result. The specific findings have their own tests that
// assert the exact message (test_scene_loader.cpp, test_obj_loader.cpp, test_partial.cpp).
#include <gtest/gtest.h>

#include <fstream>
#include <iterator>

#include "fuzz/harnesses.h"

namespace glint {
namespace {

using Harness = void (*)(const uint8_t*, size_t);

size_t replay(const std::string& name, Harness harness) {
    size_t count = 0;
    for (const char* set : {"corpus", "regressions"}) {
        const std::filesystem::path folder = std::filesystem::path(GLINT_FUZZ_DIR) / set / name;
        if (!std::filesystem::is_directory(folder)) continue;
        for (const auto& entry : std::filesystem::directory_iterator(folder)) {
            if (!entry.is_regular_file()) continue;
            std::ifstream in(entry.path(), std::ios::binary);
            const std::vector<uint8_t> bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
            EXPECT_NO_THROW(harness(bytes.data(), bytes.size())) << entry.path();
            ++count;
        }
    }
    return count;
}

TEST(FuzzCorpus, SceneInputsEndCleanly) { EXPECT_GT(replay("scene", fuzz::scene), 0u); }
TEST(FuzzCorpus, ObjInputsEndCleanly) { EXPECT_GT(replay("obj", fuzz::obj), 0u); }
TEST(FuzzCorpus, PartialInputsEndCleanly) { EXPECT_GT(replay("partial", fuzz::partial), 0u); }
TEST(FuzzCorpus, JobRequestInputsEndCleanly) { EXPECT_GT(replay("job_request", fuzz::job_request), 0u); }

}  // namespace
}  // namespace glint
