#include "http/routes.h"

#include <regex>
#include <string_view>
#include <utility>

#include "http/job_images.h"

namespace glint {
namespace {

// What each placeholder of a path matches; the captures are the handlers' req.matches[1].
constexpr std::pair<std::string_view, std::string_view> kPlaceholders[] = {
    {"{id}", "([0-9a-f]{16})"}, {"{name}", "([A-Za-z0-9_-]+)"}, {"{file}", ".*"}};

std::string replaced(std::string path, std::string_view placeholder, std::string_view by) {
    if (const size_t at = path.find(placeholder); at != std::string::npos)
        path.replace(at, placeholder.size(), by);
    return path;
}

auto image(const JobImage& image) {
    return [&image](RouteHandlers& api, const httplib::Request& req, httplib::Response& res) {
        api.image(req, res, image);
    };
}

// Each route's pattern compiled once, in the table's order.
const std::vector<std::regex>& compiled_patterns() {
    static const std::vector<std::regex> patterns = [] {
        std::vector<std::regex> all;
        for (const Route& route : routes()) all.emplace_back(path_pattern(route));
        return all;
    }();
    return patterns;
}

}  // namespace

// The page comes last: it serves whatever no other route matches.
const std::vector<Route>& routes() {
    using enum Method;
    using H = RouteHandlers;
    constexpr auto header = TokenPolicy::header_only, query = TokenPolicy::header_or_query;
    const StatusUrl unlisted;
    constexpr auto adaptive = StatusUrl::For::adaptive_jobs;  // listed for adaptive jobs only
    static const std::vector<Route> table{
        {post,    "/render",                       header, unlisted,              &H::render},
        {post,    "/jobs",                         header, unlisted,              &H::submit},
        {get,     "/jobs",                         header, unlisted,              &H::list_jobs},
        {get,     "/jobs/{id}",                    header, {"self"},              &H::show_job},
        {patch,   "/jobs/{id}",                    header, unlisted,              &H::patch},
        {delete_, "/jobs/{id}",                    header, unlisted,              &H::cancel},
        {get,     "/jobs/{id}/stream",             query,  {"stream"},            &H::stream},
        {get,     "/jobs/{id}/events",             query,  {"events"},            &H::events},
        {get,     "/jobs/{id}/image.png",          query,  {"png"},               image(kPngImage)},
        {get,     "/jobs/{id}/image.denoised.png", query,  {"denoised"},          image(kDenoisedImage)},
        {get,     "/jobs/{id}/image.pfm",          query,  {"pfm"},               image(kPfmImage)},
        {get,     "/jobs/{id}/image.exr",          query,  {"exr"},               image(kExrImage)},
        {get,     "/jobs/{id}/samples.png",        query,  {"samples", adaptive}, image(kSamplesImage)},
        {get,     "/jobs/{id}/thumbnail.png",      query,  {"thumbnail"},         image(kThumbnailImage)},
        // Outside /render and /jobs: no token is asked for (http/auth.h, needs_token).
        {get,     "/presets",                      header, unlisted,              &H::presets},
        {get,     "/presets/{name}",               header, unlisted,              &H::preset},
        {get,     "/health",                       header, unlisted,              &H::health},
        {get,     "/{file}",                       header, unlisted,              &H::page},
    };
    return table;
}

const char* method_name(Method method) {
    switch (method) {
        case Method::get: return "GET";
        case Method::post: return "POST";
        case Method::patch: return "PATCH";
        case Method::delete_: return "DELETE";
    }
    return "";
}

// A path's dots are literal ("image.png" is not "image_png"); then the placeholders' patterns.
std::string path_pattern(const Route& route) {
    std::string pattern;
    for (const char c : route.path) pattern += c == '.' ? std::string("\\.") : std::string(1, c);
    for (const auto& [placeholder, matches] : kPlaceholders)
        pattern = replaced(std::move(pattern), placeholder, matches);
    return pattern;
}

const Route* find_route(const std::string& method, const std::string& path) {
    const std::string wanted = method == "HEAD" ? "GET" : method;
    for (size_t i = 0; i < routes().size(); ++i) {
        const Route& route = routes()[i];
        if (method_name(route.method) == wanted && std::regex_match(path, compiled_patterns()[i])) return &route;
    }
    return nullptr;
}

std::string route_url(const Route& route, const std::string& id) { return replaced(route.path, "{id}", id); }

}  // namespace glint
