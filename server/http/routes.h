// The HTTP API's routes (README.md, "API"), each declared once in routes.cpp: its method and
// path, what serves it, where it takes the bearer token from and its name among the `urls` of a
// job's status. The server registers them (http/http_api.h), the token check reads their policy
// (http/auth.h) and a job's status lists their URLs (http/job_view.h) from this one table.
#pragma once

#include <functional>
#include <string>
#include <vector>

#include <httplib.h>

namespace glint {

struct JobImage;

// What serves the routes. HttpApi implements it; the table names these rather than HttpApi's
// members because HttpApi uses the token check and the job view, which read the table.
class RouteHandlers {
public:
    using Request = httplib::Request;
    using Response = httplib::Response;

    virtual void render(const Request& req, Response& res) = 0;
    virtual void submit(const Request& req, Response& res) = 0;
    virtual void list_jobs(const Request& req, Response& res) = 0;
    virtual void show_job(const Request& req, Response& res) = 0;
    virtual void patch(const Request& req, Response& res) = 0;
    virtual void cancel(const Request& req, Response& res) = 0;
    virtual void stream(const Request& req, Response& res) = 0;
    virtual void events(const Request& req, Response& res) = 0;
    // Every image route, each with what its `image` makes of the job (http/job_images.h).
    virtual void image(const Request& req, Response& res, const JobImage& image) = 0;
    virtual void presets(const Request& req, Response& res) = 0;
    virtual void preset(const Request& req, Response& res) = 0;
    virtual void health(const Request& req, Response& res) = 0;
    virtual void page(const Request& req, Response& res) = 0;

protected:
    ~RouteHandlers() = default;
};

enum class Method { get, post, patch, delete_ };

// Where a route that needs the token (http/auth.h: needs_token) takes it from. Routes that <img>
// and EventSource load cannot send headers: they take it as the query parameter `token` too.
enum class TokenPolicy { header_only, header_or_query };

// A route's entry among the `urls` of a job's status.
struct StatusUrl {
    enum class For { every_job, adaptive_jobs };
    std::string name;  // empty: not listed
    For listed_for = For::every_job;
};

struct Route {
    Method method;  // a GET route serves HEAD too, as cpp-httplib routes it
    // As README's API table writes it: {id} stands for a job's id, {name} for a preset's and
    // {file} for any path of the page's; the rest is matched as it is written (a dot is a dot).
    std::string path;
    TokenPolicy token;
    StatusUrl url;
    std::function<void(RouteHandlers&, const httplib::Request&, httplib::Response&)> handler;
};

// Every route, in the order the server tries them.
const std::vector<Route>& routes();

const char* method_name(Method method);  // "GET", ...
// The regex cpp-httplib matches a request's path with.
std::string path_pattern(const Route& route);
// The route that serves this method (HEAD as GET) and path; null if none does.
const Route* find_route(const std::string& method, const std::string& path);
// The URL of a job's route: its path with the job's id for {id}.
std::string route_url(const Route& route, const std::string& id);

}  // namespace glint
