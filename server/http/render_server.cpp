#include "http/render_server.h"

#include <chrono>

#include <spdlog/spdlog.h>

#include "http/auth.h"
#include "http/job_request.h"

namespace glint {

RenderServer::RenderServer(const ServiceConfig& service, const HttpConfig& http)
    : pool_(service.threads),
      assets_(service.asset_cache_bytes),
      jobs_(pool_, service),
      api_(jobs_, pool_, assets_, service, http),
      server_(http.request_timeout) {
    if (http.token.empty() && !is_loopback_host(http.host))
        throw std::runtime_error(
            "refusing to listen on " + http.host +
            " without a token: anyone who reaches it could run jobs; set --token or GLINT_TOKEN");
    jobs_.restore([&](const std::string& request) {
        return parse_job_request(request, service.scenes, service.scene, &assets_);
    });
    // HTTP work gets its own threads, many of them: each open stream holds one (cpp-httplib is
    // blocking), and rendering never runs on them.
    server_.new_task_queue = [n = http.threads] { return new httplib::ThreadPool(n); };
    api_.install(server_);
    listen(http);
}

void RenderServer::listen(const HttpConfig& http) {
    const std::string& host = http.host;
    port_ = http.port == 0 ? server_.bind_to_any_port(host)
                           : (server_.bind_to_port(host, http.port) ? http.port : -1);
    if (port_ < 0)
        throw std::runtime_error("cannot listen on " + host + ":" + std::to_string(http.port));
    http_ = std::thread([this] { server_.listen_after_bind(); });
    // cpp-httplib 0.11.4 hangs in stop() if it comes before the accept loop has started, so
    // return only once it runs (it does within microseconds).
    while (!server_.is_running()) std::this_thread::sleep_for(std::chrono::milliseconds(1));
    spdlog::info("glint serving on http://{}:{} ({} render threads)", host, port_, pool_.size());
}

RenderServer::~RenderServer() { stop(); }

void RenderServer::stop() {
    if (!http_.joinable()) return;
    spdlog::info("shutting down: cancelling jobs, closing streams");
    api_.shutdown();
    jobs_.shutdown();
    server_.stop();
    http_.join();
    spdlog::info("stopped");
}

}  // namespace glint
