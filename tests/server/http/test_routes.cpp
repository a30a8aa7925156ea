// The route table: which routes take the token in the query, that the token check and a job's
// status read it, and that README's API table documents every route.
#include <gtest/gtest.h>

#include <fstream>
#include <regex>
#include <set>
#include <string>

#include <nlohmann/json.hpp>

#include "http/auth.h"
#include "http/job_view.h"
#include "http/routes.h"
#include "assembly/scene_loader.h"

namespace glint {
namespace {

constexpr const char* kId = "0123456789abcdef";

std::string name_of(const Route& route) { return std::string(method_name(route.method)) + " " + route.path; }

// A path the route serves: its placeholders filled in.
std::string example_path(const Route& route) {
    std::string path = route_url(route, kId);
    for (const auto& [placeholder, example] : {std::pair{"{name}", "cornell"}, std::pair{"{file}", "index.html"}})
        if (const size_t at = path.find(placeholder); at != std::string::npos)
            path.replace(at, std::string(placeholder).size(), example);
    return path;
}

httplib::Request request(const std::string& method, const std::string& path) {
    httplib::Request req;
    req.method = method;
    req.path = path;
    return req;
}

// What an <img> or an EventSource loads: they cannot send an Authorization header.
bool loaded_by_a_browser(const Route& route) {
    const std::string& p = route.path;
    return route.method == Method::get && p.starts_with("/jobs/{id}/") &&
           (p.ends_with(".png") || p.ends_with(".pfm") || p.ends_with(".exr") || p.ends_with("/stream") ||
            p.ends_with("/events"));
}

// "METHOD /path" of every route README's API table names; `.../image.pfm` after
// `GET /jobs/{id}/image.png` is GET /jobs/{id}/image.pfm.
std::set<std::string> readme_routes() {
    std::ifstream readme(GLINT_README);
    const std::regex quoted("`([^`]*)`");
    std::set<std::string> found;
    bool in_api = false;
    for (std::string line; std::getline(readme, line);) {
        if (line.starts_with("### ")) in_api = line == "### API";
        if (!in_api || !line.starts_with("| `")) continue;
        const std::string cell = line.substr(0, line.find(" | "));
        std::string previous;
        for (std::sregex_iterator it(cell.begin(), cell.end(), quoted), end; it != end; ++it) {
            std::string route = (*it)[1];
            if (route.starts_with("...")) route = previous.substr(0, previous.rfind('/')) + route.substr(3);
            found.insert(route);
            previous = route;
        }
    }
    return found;
}

TEST(Routes, OnlyWhatABrowserLoadsTakesTheTokenInTheQuery) {
    for (const Route& route : routes())
        EXPECT_EQ(route.token == TokenPolicy::header_or_query, loaded_by_a_browser(route)) << name_of(route);
}

// Each route serves its own paths (none before it in the table takes them), and the token
// check takes its policy from the route that serves the request.
TEST(Routes, TheTokenCheckReadsThePolicyOfTheRouteThatServesTheRequest) {
    for (const Route& route : routes()) {
        const httplib::Request req = request(method_name(route.method), example_path(route));
        EXPECT_EQ(find_route(req.method, req.path), &route) << name_of(route);
        EXPECT_EQ(token_in_query_allowed(req), route.token == TokenPolicy::header_or_query) << name_of(route);
    }
    const std::string job = std::string("/jobs/") + kId;
    EXPECT_TRUE(token_in_query_allowed(request("HEAD", job + "/image.png")));
    EXPECT_FALSE(token_in_query_allowed(request("POST", job + "/image.png")));
    EXPECT_FALSE(token_in_query_allowed(request("GET", "/jobs/nope/image.png")));  // the page's path
    EXPECT_EQ(find_route("GET", job + "/image_png"), &routes().back());  // a dot is a dot: the page's too
}

TEST(Routes, ReadmesApiTableDocumentsEveryRoute) {
    const std::set<std::string> documented = readme_routes();
    ASSERT_TRUE(documented.contains("GET /jobs/{id}/image.pfm")) << "README's API table not found";
    for (const Route& route : routes()) EXPECT_TRUE(documented.contains(name_of(route))) << name_of(route);
}

// Every URL in a status leads to the route of its name, and every route with a name is there
// (samples.png for adaptive jobs only).
TEST(Routes, AJobsStatusListsTheTablesUrls) {
    LoadedScene scene = load_scene(GLINT_SCENES_DIR "/cornell.json");
    for (const double threshold : {0.0, 0.2}) {
        scene.settings.adaptive.threshold = threshold;
        const nlohmann::json urls = job_status(Job(kId, scene))["urls"];
        std::set<std::string> listed, named;
        for (const auto& [name, url] : urls.items()) {
            const Route* route = find_route("GET", url.get<std::string>());
            ASSERT_NE(route, nullptr) << url;
            EXPECT_EQ(route->url.name, name);
            listed.insert(name);
        }
        for (const Route& route : routes())
            if (!route.url.name.empty() && (threshold > 0 || route.url.listed_for == StatusUrl::For::every_job))
                named.insert(route.url.name);
        EXPECT_EQ(listed, named);
        std::set<std::string> expected{"self", "png", "denoised", "pfm", "exr", "stream", "events", "thumbnail"};
        if (threshold > 0) expected.insert("samples");
        EXPECT_EQ(listed, expected);
    }
}

}  // namespace
}  // namespace glint
