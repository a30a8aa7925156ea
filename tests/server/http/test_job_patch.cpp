// PATCH /jobs/{id} bodies: the one field, its range, and the service's error for each mistake.
#include <gtest/gtest.h>

#include "http/job_patch.h"
#include "service/errors.h"
#include "service/priority.h"

namespace glint {
namespace {

// "KIND PATH: MESSAGE" of the error, or "ok".
std::string error_of(const std::string& body) {
    try {
        parse_job_patch(body);
    } catch (const ServiceError& e) {
        const char* kind = e.kind() == ServiceError::Kind::malformed ? "malformed" : e.kind() == ServiceError::Kind::invalid ? "invalid" : "other";
        return std::string(kind) + " " + e.path() + ": " + e.what();
    }
    return "ok";
}

TEST(JobPatch, ReadsThePriority) {
    EXPECT_EQ(parse_job_patch(R"({"priority": 3})").priority, 3);
    EXPECT_EQ(parse_job_patch(R"({"priority": -10})").priority, kMinPriority);
    EXPECT_EQ(parse_job_patch(R"({"priority": 10} )").priority, kMaxPriority);
    EXPECT_FALSE(parse_job_patch("{}").priority);
}

TEST(JobPatch, RefusesEveryOtherBody) {
    const std::string range = "invalid priority: must be an integer in [-10, 10]";
    EXPECT_EQ(error_of(R"({"priority": 11})"), range);
    EXPECT_EQ(error_of(R"({"priority": -11})"), range);
    EXPECT_EQ(error_of(R"({"priority": 2.0})"), range);
    EXPECT_EQ(error_of(R"({"priority": "3"})"), range);
    EXPECT_EQ(error_of(R"({"priority": null})"), range);
    // Read as int64_t, this one would be -1.
    EXPECT_EQ(error_of(R"({"priority": 18446744073709551615})"), range);
    EXPECT_EQ(error_of(R"({"priority": 1, "spp": 4})"), "invalid spp: unknown field (expected: priority)");
    EXPECT_EQ(error_of("[1]"), "invalid : must be an object");
    EXPECT_EQ(error_of(R"({"priority": 1)"),
              "malformed : malformed JSON at byte 15: syntax error while parsing object - unexpected end of input; "
              "expected '}'");
    EXPECT_EQ(error_of(std::string("{\"priority\": 1}\0{\"priority\": 99}", 32)), "malformed : malformed JSON at byte 16: NUL byte");
}

TEST(Priority, EachStepDoublesTheWeight) {
    EXPECT_EQ(priority_weight(0), 1.0);
    EXPECT_EQ(priority_weight(1), 2.0);
    EXPECT_EQ(priority_weight(-1), 0.5);
    EXPECT_EQ(priority_weight(kMaxPriority) / priority_weight(kMinPriority), 1048576.0);
}

}  // namespace
}  // namespace glint
