// JSON text from outside glint (a scene file, a request body): one value, nested at most
// kMaxJsonDepth levels, with nothing after it but whitespace. Every caller parses through here,
// so the bounds and the messages are the same for a file on disk and a body over HTTP.
#pragma once

#include <stdexcept>
#include <string>

#include <nlohmann/json_fwd.hpp>

namespace glint {

// JSON nested deeper is refused while parsing, before it can cost stack or memory.
inline constexpr int kMaxJsonDepth = 32;

// Text that is not one acceptable JSON value. Its message names the byte at fault, counting
// from 1 as nlohmann's parse_error::byte does: "malformed JSON at byte 12: syntax error while
// parsing value - ...", "malformed JSON at byte 3: NUL byte"; or it is "JSON nested deeper than
// 32 levels", which the parser cannot place.
class JsonTextError : public std::runtime_error {
public:
    using std::runtime_error::runtime_error;
};

// Throws JsonTextError.
nlohmann::json parse_json_text(const std::string& text);

}  // namespace glint
