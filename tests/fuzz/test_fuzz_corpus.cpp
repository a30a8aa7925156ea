// Replays the fuzzers' seed corpus and every input they ever crashed on (tests/fuzz/regressions/)
// through the harnesses, in the normal build and under .ci/sanitizers: each must end in the
// parser's own clean error or a valid result; and each crashing input in the exact error it
// must give.
#include <gtest/gtest.h>

#include <fstream>
#include <iterator>

#include "assembly/fingerprint.h"
#include "assembly/partial_file.h"
#include "assembly/scene_loader.h"
#include "fuzz/harnesses.h"
#include "http/job_request.h"
#include "service/service_config.h"

namespace glint {
namespace {

using Harness = void (*)(const uint8_t*, size_t);

std::vector<uint8_t> read_input(const std::filesystem::path& file) {
    std::ifstream in(file, std::ios::binary);
    return std::vector<uint8_t>((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
}

size_t replay(const std::string& name, Harness harness) {
    size_t count = 0;
    for (const char* set : {"corpus", "regressions"}) {
        const std::filesystem::path folder = std::filesystem::path(GLINT_FUZZ_DIR) / set / name;
        if (!std::filesystem::is_directory(folder)) continue;
        for (const auto& entry : std::filesystem::directory_iterator(folder)) {
            if (!entry.is_regular_file()) continue;
            const std::vector<uint8_t> bytes = read_input(entry.path());
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
TEST(FuzzCorpus, QueryInputsEndCleanly) { EXPECT_GT(replay("query", fuzz::query), 0u); }
TEST(FuzzCorpus, JobPatchInputsEndCleanly) { EXPECT_GT(replay("job_patch", fuzz::job_patch), 0u); }
TEST(FuzzCorpus, TextureInputsEndCleanly) { EXPECT_GT(replay("texture", fuzz::texture), 0u); }

// Each input that crashed a harness, fed to the parser it crashed, ends in its clean error.
template <typename Error, typename Parse>
std::string error_from(const std::string& file, Parse parse) {
    const std::vector<uint8_t> bytes = read_input(std::filesystem::path(GLINT_FUZZ_DIR) / "regressions" / file);
    try {
        parse(bytes);
    } catch (const Error& e) {
        return e.what();
    }
    return "no error";
}

std::vector<uint8_t> with_checksum(std::vector<uint8_t> bytes) {  // as the partial harness does
    Fnv1a h;
    h.bytes(bytes.data(), bytes.size());
    const uint64_t sum = h.digest();
    const auto* p = reinterpret_cast<const uint8_t*>(&sum);
    bytes.insert(bytes.end(), p, p + sizeof sum);
    return bytes;
}

TEST(FuzzRegressions, EachCrashingInputEndsInItsCleanError) {
    auto text = [](const std::vector<uint8_t>& b) { return std::string(b.begin(), b.end()); };
    EXPECT_EQ(error_from<SceneError>("scene/number-overflow.json",
                                     [&](const auto& b) { parse_scene(text(b), fuzz::mesh_folder()); }),
              "malformed JSON at byte 25: number overflow parsing '1e2612'");
    EXPECT_EQ(error_from<ServiceError>("job_request/number-overflow.json", [&](const auto& b) {
                  parse_job_request(text(b), fuzz::scenes_folder(), ServiceConfig{}.scene);
              }),
              "malformed JSON at byte 34: number overflow parsing '1e999'");
    EXPECT_EQ(error_from<PartialError>("partial/unknown-encoding.bin",
                                       [](const auto& b) { decode_partial(with_checksum(b)); }),
              "unknown PNG encoding 168 (0 gamma 2.2, 1 sRGB)");
    EXPECT_EQ(error_from<PartialError>("partial/size-overflow.bin", [](const auto& b) { decode_partial(with_checksum(b)); }),
              "size does not match the header");
}

}  // namespace
}  // namespace glint
