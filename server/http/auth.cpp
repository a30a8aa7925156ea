#include "http/auth.h"

#include <arpa/inet.h>

#include "http/routes.h"

namespace glint {

bool is_loopback_host(const std::string& host) {
    if (host == "localhost") return true;
    in_addr v4{};
    if (::inet_pton(AF_INET, host.c_str(), &v4) == 1) return (ntohl(v4.s_addr) >> 24) == 127;
    in6_addr v6{};
    if (::inet_pton(AF_INET6, host.c_str(), &v6) != 1) return false;
    if (IN6_IS_ADDR_LOOPBACK(&v6)) return true;
    return IN6_IS_ADDR_V4MAPPED(&v6) && v6.s6_addr[12] == 127;
}

bool same_secret(std::string_view given, std::string_view expected) {
    unsigned diff = given.size() != expected.size();
    for (size_t i = 0; i < expected.size(); ++i)
        diff |= unsigned(static_cast<unsigned char>(i < given.size() ? given[i] : 0) ^ static_cast<unsigned char>(expected[i]));
    return diff == 0;
}

bool needs_token(const std::string& path) { return path == "/render" || path == "/jobs" || path.starts_with("/jobs/"); }

bool token_in_query_allowed(const httplib::Request& req) {
    const Route* route = find_route(req.method, req.path);
    return route && route->token == TokenPolicy::header_or_query;
}

std::string check_token(const httplib::Request& req, const std::string& token) {
    if (token.empty() || !needs_token(req.path)) return "";
    const std::string header = req.get_header_value("Authorization");
    constexpr std::string_view scheme = "Bearer ";
    if (header.size() > scheme.size() && header.starts_with(scheme))
        return same_secret(std::string_view(header).substr(scheme.size()), token) ? "" : "wrong bearer token";
    if (!header.empty()) return "the Authorization header must be \"Bearer TOKEN\"";
    if (req.has_param("token")) {
        if (!token_in_query_allowed(req)) return "the token may be a query parameter only on stream, events and image routes";
        return same_secret(req.get_param_value("token"), token) ? "" : "wrong bearer token";
    }
    return "this server needs a bearer token (header Authorization: Bearer TOKEN)";
}

}  // namespace glint
