// The HTTP layer's configuration: where it listens, who may use it and what one request, client
// and connection may hold. `glint serve` fills it from its options; job limits are the
// service's (service/service_config.h).
#pragma once

#include <chrono>
#include <cstddef>
#include <filesystem>
#include <string>

namespace glint {

struct HttpConfig {
    // This machine only by default: a server reachable from others needs a token (below).
    std::string host = "127.0.0.1";
    // 0: any free port (the tests take one so that they can run side by side).
    int port = 8080;
    // The page's folder, served at / (http/static_files.h).
    std::filesystem::path web = "web";
    // When set, job routes need "Authorization: Bearer TOKEN" (http/auth.h); required off
    // loopback, where anyone who reaches the port could otherwise run jobs.
    std::string token;
    // Largest request body: a scene with inline meshes of tens of thousands of triangles fits,
    // while one client cannot make the server buffer unbounded bodies.
    size_t max_body_bytes = size_t(16) << 20;
    // Open streams (PNG frames, events) in total; beyond, 503. Each holds an HTTP thread while
    // open (cpp-httplib is blocking), so this stays well below `threads`.
    size_t max_streams = 32;
    // Open streams per remote address; beyond, 429. The page holds 2 per job it shows.
    size_t streams_per_client = 8;
    // Request line, headers and body together must arrive within this, or 408: a client sending
    // one byte a second must not hold an HTTP thread forever (http/guarded_server.h).
    std::chrono::milliseconds request_timeout{20000};
    // HTTP threads, many of them: each open stream holds one, and rendering never runs on them.
    size_t threads = 64;
};

}  // namespace glint
