// The HTTP API of `glint serve` (routes documented in README.md) on cpp-httplib. Handlers
// never wait on rendering: they read job snapshots, and the streaming responses poll them.
#pragma once

#include <atomic>
#include <filesystem>

#include <httplib.h>

#include "job_manager.h"
#include "job_store.h"

namespace glint {

struct ServiceConfig {
    std::filesystem::path scenes = "scenes";
    std::filesystem::path web = "web";
    ServiceLimits limits;
    StoreConfig store;  // --store: jobs survive a restart (job_store.h)
};

class HttpApi {
public:
    HttpApi(JobManager& jobs, ThreadPool& pool, ServiceConfig config);
    // Installs routes, limits, timeouts, JSON error bodies and request logging on `server`.
    void install(httplib::Server& server);
    // Makes open streams send their closing parts and end, so the server can stop.
    void shutdown() { stopping_ = true; }

private:
    void submit(const httplib::Request& req, httplib::Response& res);
    void render(const httplib::Request& req, httplib::Response& res);
    void stream(const std::shared_ptr<Job>& job, httplib::Response& res);
    void events(const std::shared_ptr<Job>& job, httplib::Response& res);
    std::shared_ptr<Job> job_or_404(const httplib::Request& req, httplib::Response& res) const;
    std::shared_ptr<Job> accept(const httplib::Request& req, httplib::Response& res);
    bool admit_stream(httplib::Response& res);

    JobManager& jobs_;
    ThreadPool& pool_;
    ServiceConfig config_;
    std::atomic<size_t> open_streams_{0};
    std::atomic<bool> stopping_{false};
};

}  // namespace glint
