// A running render service: the render pool, the job manager and the HTTP server on its own
// thread. `glint serve` runs one until a signal; the tests start one on a free port.
#pragma once

#include <memory>
#include <thread>

#include "guarded_server.h"
#include "http_api.h"

namespace glint {

class Service {
public:
    // Binds host:port (port 0: any free port) or throws std::runtime_error.
    Service(const ServiceConfig& config, const std::string& host, int port, unsigned render_threads);
    ~Service();  // stop()

    int port() const { return port_; }
    // Graceful: refuse new work, cancel jobs, let streams send their last part, then stop.
    void stop();

private:
    ThreadPool pool_;
    JobManager jobs_;
    HttpApi api_;
    GuardedServer server_;
    int port_ = 0;
    std::thread http_;
};

}  // namespace glint
