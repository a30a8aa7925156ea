// A running render server: the render pool, the job manager and the HTTP server on its own
// thread. `glint serve` runs one until a signal; the tests start one on a free port.
#pragma once

#include <memory>
#include <thread>

#include "http/guarded_server.h"
#include "http/http_api.h"
#include "http/http_config.h"
#include "service/service_config.h"

namespace glint {

class RenderServer {
public:
    // Binds http.host:http.port (port 0: any free port) or throws std::runtime_error.
    RenderServer(const ServiceConfig& service, const HttpConfig& http);
    ~RenderServer();  // stop()

    int port() const { return port_; }
    // Graceful: refuse new work, cancel jobs, let streams send their last part, then stop.
    void stop();

private:
    void listen(const HttpConfig& http);

    ThreadPool pool_;
    AssetCache assets_;  // decoded files, shared by the jobs that use them
    JobManager jobs_;
    HttpApi api_;
    GuardedServer server_;
    int port_ = 0;
    std::thread http_;
};

}  // namespace glint
