// The HTTP API of `glint serve` on cpp-httplib: the handlers of its routes (http/routes.h,
// documented in README.md). Handlers never wait on rendering: they read job snapshots, and the
// streaming responses poll them.
#pragma once

#include <atomic>
#include <chrono>
#include <filesystem>
#include <map>
#include <mutex>

#include <httplib.h>

#include "http/http_config.h"
#include "http/routes.h"
#include "service/job_manager.h"
#include "service/service_config.h"

namespace glint {

class HttpApi final : public RouteHandlers {
public:
    // `service` for the scenes folder and what one job may ask for.
    // `assets`: the server's cache of decoded files, shared by every request.
    HttpApi(JobManager& jobs, ThreadPool& pool, AssetCache& assets, const ServiceConfig& service, HttpConfig config);
    // Installs routes, limits, timeouts, JSON error bodies and request logging on `server`.
    void install(httplib::Server& server);
    // Makes open streams send their closing parts and end, so the server can stop.
    void shutdown() { stopping_ = true; }

private:
    void install_limits(httplib::Server& server) const;
    void install_hooks(httplib::Server& server);
    void install_routes(httplib::Server& server);
    void render(const Request& req, Response& res) override;
    void submit(const Request& req, Response& res) override;
    void list_jobs(const Request& req, Response& res) override;
    void show_job(const Request& req, Response& res) override;
    void patch(const Request& req, Response& res) override;
    void cancel(const Request& req, Response& res) override;
    void stream(const Request& req, Response& res) override;
    void events(const Request& req, Response& res) override;
    void image(const Request& req, Response& res, const JobImage& image) override;
    void presets(const Request& req, Response& res) override;
    void preset(const Request& req, Response& res) override;
    void health(const Request& req, Response& res) override;
    void page(const Request& req, Response& res) override;
    std::shared_ptr<Job> job_or_404(const httplib::Request& req, httplib::Response& res) const;
    std::shared_ptr<Job> accept(const httplib::Request& req, httplib::Response& res);
    bool admit_stream(const httplib::Request& req, httplib::Response& res);
    void release_stream(const std::string& client);

    JobManager& jobs_;
    ThreadPool& pool_;
    AssetCache& assets_;
    std::filesystem::path scenes_;
    SceneLimits scene_limits_;
    HttpConfig config_;
    std::atomic<size_t> open_streams_{0};
    std::mutex clients_mutex_;
    std::map<std::string, size_t> streams_by_client_;  // remote address -> open streams
    std::atomic<bool> stopping_{false};
};

}  // namespace glint
