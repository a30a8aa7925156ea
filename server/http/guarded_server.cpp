#include "http/guarded_server.h"

#include <arpa/inet.h>
#include <netdb.h>
#include <poll.h>
#include <sys/socket.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstring>

#include <nlohmann/json.hpp>

namespace glint {
namespace {

using Clock = std::chrono::steady_clock;
using std::chrono::milliseconds;

// Waits until the socket is ready for `events`, at most `timeout`; retries on signals.
bool wait_ready(int sock, short events, milliseconds timeout) {
    pollfd p{sock, events, 0};
    const auto end = Clock::now() + timeout;
    for (;;) {
        const auto left = std::chrono::duration_cast<milliseconds>(end - Clock::now()).count();
        const int n = ::poll(&p, 1, int(std::max<int64_t>(left, 0)));
        if (n >= 0 || errno != EINTR) return n > 0;
    }
}

void address_of(int sock, bool peer, std::string& ip, int& port) {
    sockaddr_storage addr{};
    socklen_t length = sizeof addr;
    auto* a = reinterpret_cast<sockaddr*>(&addr);
    if ((peer ? ::getpeername(sock, a, &length) : ::getsockname(sock, a, &length)) != 0) return;
    char host[NI_MAXHOST], service[NI_MAXSERV];
    if (::getnameinfo(a, length, host, sizeof host, service, sizeof service, NI_NUMERICHOST | NI_NUMERICSERV) != 0)
        return;
    ip = host;
    port = std::atoi(service);
}

// One connection's socket as cpp-httplib's Stream: buffered reads that stop at the current
// request's deadline, writes bounded by the write timeout.
class DeadlineStream final : public httplib::Stream {
public:
    DeadlineStream(int sock, milliseconds read_timeout, milliseconds write_timeout)
        : sock_(sock), read_timeout_(read_timeout), write_timeout_(write_timeout) {}

    // Waits for the first byte of the next request (at most `idle`, or until `stopping`).
    template <typename Stopping>
    bool wait_for_request(milliseconds idle, Stopping stopping) {
        const auto end = Clock::now() + idle;
        while (begin_ == end_ && !stopping()) {
            if (wait_ready(sock_, POLLIN, milliseconds(100))) return true;
            if (Clock::now() >= end) return false;
        }
        return begin_ != end_;
    }
    void start_request(Clock::time_point deadline) {
        deadline_ = deadline;
        timed_out_ = wrote_ = close_ = false;
    }
    bool timed_out() const { return timed_out_; }
    bool wrote() const { return wrote_; }
    bool close_requested() const { return close_; }
    void request_close() { close_ = true; }

    bool is_readable() const override { return begin_ != end_ || wait_ready(sock_, POLLIN, read_wait()); }
    bool is_writable() const override { return wait_ready(sock_, POLLOUT, write_timeout_) && peer_alive(); }

    ssize_t read(char* ptr, size_t size) override {
        if (begin_ == end_) {
            const milliseconds wait = read_wait();
            if (wait.count() <= 0 || !wait_ready(sock_, POLLIN, wait)) {
                timed_out_ = wait < read_timeout_;  // the deadline, not the idle timeout, ended the wait
                return -1;
            }
            ssize_t n;
            do n = ::recv(sock_, buffer_, sizeof buffer_, 0);
            while (n < 0 && errno == EINTR);
            if (n <= 0) return n;
            begin_ = 0;
            end_ = size_t(n);
        }
        const size_t n = std::min(size, end_ - begin_);
        std::memcpy(ptr, buffer_ + begin_, n);
        begin_ += n;
        return ssize_t(n);
    }
    ssize_t write(const char* ptr, size_t size) override {
        if (!wait_ready(sock_, POLLOUT, write_timeout_)) return -1;
        ssize_t n;
        do n = ::send(sock_, ptr, size, MSG_NOSIGNAL);
        while (n < 0 && errno == EINTR);
        wrote_ |= n > 0;
        return n;
    }
    void get_remote_ip_and_port(std::string& ip, int& port) const override { address_of(sock_, true, ip, port); }
    void get_local_ip_and_port(std::string& ip, int& port) const override { address_of(sock_, false, ip, port); }
    socket_t socket() const override { return sock_; }

private:
    milliseconds read_wait() const {
        const auto left = std::chrono::duration_cast<milliseconds>(deadline_ - Clock::now());
        return std::min(left, read_timeout_);
    }
    // A readable socket with nothing to read has been closed by the peer.
    bool peer_alive() const {
        if (begin_ != end_ || !wait_ready(sock_, POLLIN, milliseconds(0))) return true;
        char byte;
        return ::recv(sock_, &byte, 1, MSG_PEEK | MSG_DONTWAIT) > 0;
    }

    int sock_;
    milliseconds read_timeout_, write_timeout_;
    Clock::time_point deadline_{};
    bool timed_out_ = false, wrote_ = false, close_ = false;
    char buffer_[4096];
    size_t begin_ = 0, end_ = 0;
};

thread_local DeadlineStream* t_stream = nullptr;

// When the request line itself did not arrive in time, cpp-httplib answers nothing; say why.
void send_timeout(DeadlineStream& stream, milliseconds timeout) {
    const std::string body =
        nlohmann::json{{"error", "request not received within " + std::to_string(timeout.count()) + " ms"}}.dump();
    const std::string response = "HTTP/1.1 408 Request Timeout\r\nContent-Type: application/json\r\nContent-Length: " +
                                 std::to_string(body.size()) + "\r\nConnection: close\r\n\r\n" + body;
    stream.write(response.data(), response.size());
}

}  // namespace

bool GuardedServer::request_timed_out() { return t_stream && t_stream->timed_out(); }

void GuardedServer::close_after_response() {
    if (t_stream) t_stream->request_close();
}

// cpp-httplib's keep-alive loop, with the request deadline and the 408 added.
bool GuardedServer::process_and_close_socket(socket_t sock) {
    using std::chrono::seconds;
    using std::chrono::microseconds;
    DeadlineStream stream(sock, std::chrono::duration_cast<milliseconds>(seconds(read_timeout_sec_) + microseconds(read_timeout_usec_)),
                          std::chrono::duration_cast<milliseconds>(seconds(write_timeout_sec_) + microseconds(write_timeout_usec_)));
    t_stream = &stream;
    for (size_t left = keep_alive_max_count_; left > 0; --left) {
        if (!stream.wait_for_request(seconds(keep_alive_timeout_sec_), [this] { return svr_sock_ == INVALID_SOCKET; }))
            break;
        stream.start_request(Clock::now() + request_timeout_);
        bool closed = false;
        const bool ok = process_request(stream, left == 1, closed, nullptr);
        if (stream.timed_out() && !stream.wrote()) send_timeout(stream, request_timeout_);
        if (!ok || closed || stream.timed_out() || stream.close_requested()) break;
    }
    t_stream = nullptr;
    ::shutdown(sock, SHUT_RDWR);
    ::close(sock);
    return true;
}

}  // namespace glint
