// Job request bodies as JSON: what follows the value, and where a malformed body goes wrong.
// (Each field's checks are the scene loader's and the API tests'.)
#include <gtest/gtest.h>

#include "http/job_request.h"
#include "service/service_config.h"

namespace glint {
namespace {

// The error's kind and message, or "ok".
std::string outcome_of(const std::string& body) {
    try {
        parse_job_request(body, GLINT_SCENES_DIR, ServiceConfig{}.scene);
    } catch (const ServiceError& e) {
        return std::string(e.kind() == ServiceError::Kind::malformed ? "malformed: " : "other: ") + e.what();
    }
    return "ok";
}

constexpr const char* kPreset = R"({"preset": "cornell", "width": 16, "height": 12, "spp": 4})";

TEST(JobRequest, TrailingWhitespaceIsAccepted) {
    EXPECT_EQ(outcome_of(std::string(kPreset) + " \r\n\t"), "ok");
    EXPECT_EQ(outcome_of(R"({"film": {"width": 8, "height": 6}}  )"), "ok");
}

// nlohmann reads a NUL byte as the end of the input: a body with a NUL after the value and more
// bytes behind it was a valid request.
TEST(JobRequest, ANulByteOrTrailingBytesAreMalformedAtTheirOffset) {
    EXPECT_EQ(outcome_of(std::string(kPreset) + std::string("\0{\"spp\": 65536}", 15)),
              "malformed: malformed JSON at byte 59: NUL byte");
    EXPECT_EQ(outcome_of(std::string(R"({"film": {}})") + std::string("\0", 1)),
              "malformed: malformed JSON at byte 13: NUL byte");
    EXPECT_EQ(outcome_of(std::string(kPreset) + " garbage"),
              "malformed: malformed JSON at byte 60: syntax error while parsing value - invalid literal; last read: "
              "'4} g'; expected end of input");
}

TEST(JobRequest, APresetAsksForAovsWithABoolean) {
    EXPECT_FALSE(parse_job_request(kPreset, GLINT_SCENES_DIR, ServiceConfig{}.scene).scene.settings.aovs);
    const std::string with = R"({"preset": "cornell", "width": 16, "height": 12, "spp": 4, "aovs": true})";
    EXPECT_TRUE(parse_job_request(with, GLINT_SCENES_DIR, ServiceConfig{}.scene).scene.settings.aovs);
    try {
        parse_job_request(R"({"preset": "cornell", "aovs": "yes"})", GLINT_SCENES_DIR, ServiceConfig{}.scene);
        FAIL() << "accepted";
    } catch (const InvalidRequest& e) {
        EXPECT_EQ(e.path(), "aovs");
        EXPECT_EQ(std::string(e.what()), "must be true or false");
    }
}

TEST(JobRequest, EveryMalformedBodyNamesItsByte) {
    EXPECT_EQ(outcome_of(R"({"preset": )"),
              "malformed: malformed JSON at byte 12: syntax error while parsing value - unexpected end of input; "
              "expected '[', '{', or a literal");
    EXPECT_EQ(outcome_of(R"({"preset": "cornell", "spp": 1e999})"),
              "malformed: malformed JSON at byte 34: number overflow parsing '1e999'");
}

}  // namespace
}  // namespace glint
