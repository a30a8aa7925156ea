// JSON text from outside: the same document as nlohmann's own parser builds, the nesting bound,
// and every refusal naming the byte at fault, a NUL byte and trailing bytes included.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include "io/json_text.h"

namespace glint {
namespace {

std::string error_of(const std::string& text) {
    try {
        parse_json_text(text);
    } catch (const JsonTextError& e) {
        return e.what();
    }
    return "no error";
}

TEST(JsonText, BuildsTheDocumentNlohmannBuilds) {
    const std::string text = R"({"a": [1, -2, 3.5, "x", true, false, null, [], {}, [[{"b": {"c": [0]}}]]],
                               "d": {"e": 18446744073709551615, "f": -9223372036854775808},
                               "g": "\u00e9\n", "a2": {}, "d": 7})";  // a repeated key: the last wins
    EXPECT_EQ(parse_json_text(text), nlohmann::json::parse(text));
    EXPECT_EQ(parse_json_text(" 42 "), nlohmann::json(42));
}

TEST(JsonText, NestingIsBoundedWhileParsing) {
    EXPECT_NO_THROW(parse_json_text(std::string(kMaxJsonDepth, '[') + std::string(kMaxJsonDepth, ']')));
    EXPECT_EQ(error_of(std::string(kMaxJsonDepth + 1, '[') + std::string(kMaxJsonDepth + 1, ']')),
              "JSON nested deeper than 32 levels");
    EXPECT_EQ(error_of(std::string(100000, '{')), "malformed JSON at byte 2: syntax error while parsing object key - "
                                                   "unexpected '{'; expected string literal");
}

TEST(JsonText, OnlyWhitespaceMayFollowTheValue) {
    EXPECT_EQ(parse_json_text("{\"a\": 1} \t\r\n"), nlohmann::json({{"a", 1}}));
    // nlohmann alone reads the NUL as the end of the input and accepts this.
    EXPECT_EQ(error_of(std::string("{\"a\": 1}\0trailing", 17)), "malformed JSON at byte 9: NUL byte");
    EXPECT_EQ(error_of(std::string("{\"a\": 1} \0", 10)), "malformed JSON at byte 10: NUL byte");
    EXPECT_EQ(error_of(std::string("{\"a\": \"\0\"}", 10)), "malformed JSON at byte 8: NUL byte");
    EXPECT_EQ(error_of("{\"a\": 1} x"), "malformed JSON at byte 10: syntax error while parsing value - invalid literal; "
                                        "last read: '1} x'; expected end of input");
    EXPECT_EQ(error_of("{\"a\": 1}{}"), "malformed JSON at byte 9: syntax error while parsing value - unexpected '{'; "
                                        "expected end of input");
}

TEST(JsonText, EveryMalformedTextNamesItsByte) {
    EXPECT_EQ(error_of(""), "malformed JSON at byte 1: syntax error while parsing value - unexpected end of input; "
                            "expected '[', '{', or a literal");
    EXPECT_EQ(error_of("{\"a\":\n 1e999}"), "malformed JSON at byte 12: number overflow parsing '1e999'");
    EXPECT_EQ(error_of("[1, 2,]").rfind("malformed JSON at byte 7: ", 0), 0u);
}

}  // namespace
}  // namespace glint
