// cpp-httplib's server with a deadline on reading each request. Its own read timeout bounds
// each recv() only, so a client sending one byte a second would hold an HTTP thread forever;
// here the request line, headers and body together must arrive within `request_timeout`, or
// the client gets a 408 and the connection is closed. Writes never raise SIGPIPE.
#pragma once

#include <chrono>

#include <httplib.h>

namespace glint {

class GuardedServer : public httplib::Server {
public:
    explicit GuardedServer(std::chrono::milliseconds request_timeout) : request_timeout_(request_timeout) {}

    // For handlers on the connection's thread: did reading the current request run out of time?
    static bool request_timed_out();
    // Closes the connection once the current response is written (e.g. after refusing a request
    // whose body was never read).
    static void close_after_response();

private:
    bool process_and_close_socket(socket_t sock) override;

    std::chrono::milliseconds request_timeout_;
};

}  // namespace glint
