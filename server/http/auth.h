// Bearer tokens: a server reachable from other machines admits to its job routes only requests
// that carry the token it was started with.
#pragma once

#include <string>
#include <string_view>

#include <httplib.h>

namespace glint {

// 127.0.0.0/8, ::1 (also as ::ffff:127.x.y.z) and the name "localhost". Any other name counts
// as reachable from outside, whatever it resolves to.
bool is_loopback_host(const std::string& host);

// Compares in time that depends only on the expected token's length.
bool same_secret(std::string_view given, std::string_view expected);

// Routes that start, cancel or read jobs need the token; the page, presets and /health do not.
bool needs_token(const std::string& path);
// Whether the route that serves the request takes the token as the query parameter `token`
// too (its TokenPolicy, http/routes.h): those that <img>, <a> and EventSource load.
bool token_in_query_allowed(const httplib::Request& req);

// Empty when the request may proceed (no token set, a route that needs none, or the right
// token), else why not (answered with 401). Reads the query parameters cpp-httplib parsed from
// the request target (fuzzed through the server's own parsing: tests/fuzz, harness `query`).
std::string check_token(const httplib::Request& req, const std::string& token);

}  // namespace glint
