// The HTTP API of `glint serve` (routes documented in README.md) on cpp-httplib. Handlers
// never wait on rendering: they read job snapshots, and the streaming responses poll them.
#pragma once

#include <atomic>
#include <chrono>
#include <filesystem>
#include <map>
#include <mutex>

#include <httplib.h>

#include "job_manager.h"
#include "job_store.h"

namespace glint {

// What one client and one connection may hold (job limits are in ServiceLimits).
struct HttpLimits {
    size_t streams_per_client = 8;  // per remote address; the page holds 2 per job it shows
    std::chrono::milliseconds request_timeout{20000};  // request line, headers and body together
    size_t threads = 64;  // HTTP threads: each open stream holds one (cpp-httplib is blocking)
};

struct ServiceConfig {
    std::filesystem::path scenes = "scenes";
    std::filesystem::path web = "web";
    ServiceLimits limits;
    StoreConfig store;  // --store: jobs survive a restart (job_store.h)
    HttpLimits http;
    std::string token;  // when set, job routes need "Authorization: Bearer TOKEN" (see auth.h)
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
    void stream(const httplib::Request& req, const std::shared_ptr<Job>& job, httplib::Response& res);
    void events(const httplib::Request& req, const std::shared_ptr<Job>& job, httplib::Response& res);
    std::shared_ptr<Job> job_or_404(const httplib::Request& req, httplib::Response& res) const;
    std::shared_ptr<Job> accept(const httplib::Request& req, httplib::Response& res);
    bool admit_stream(const httplib::Request& req, httplib::Response& res);
    void release_stream(const std::string& client);

    JobManager& jobs_;
    ThreadPool& pool_;
    ServiceConfig config_;
    std::atomic<size_t> open_streams_{0};
    std::mutex clients_mutex_;
    std::map<std::string, size_t> streams_by_client_;  // remote address -> open streams
    std::atomic<bool> stopping_{false};
};

}  // namespace glint
