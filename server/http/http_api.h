// The HTTP API of `glint serve` (routes documented in README.md) on cpp-httplib. Handlers
// never wait on rendering: they read job snapshots, and the streaming responses poll them.
#pragma once

#include <atomic>
#include <chrono>
#include <filesystem>
#include <map>
#include <mutex>

#include <httplib.h>

#include "http/http_config.h"
#include "service/job_manager.h"
#include "service/service_config.h"

namespace glint {

class HttpApi {
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
    void install_job_routes(httplib::Server& server);
    void install_image_routes(httplib::Server& server);
    void install_other_routes(httplib::Server& server);
    void submit(const httplib::Request& req, httplib::Response& res);
    void render(const httplib::Request& req, httplib::Response& res);
    void patch(const httplib::Request& req, httplib::Response& res);
    void stream(const httplib::Request& req, const std::shared_ptr<Job>& job, httplib::Response& res);
    void events(const httplib::Request& req, const std::shared_ptr<Job>& job, httplib::Response& res);
    void denoised(const std::shared_ptr<Job>& job, httplib::Response& res);
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
