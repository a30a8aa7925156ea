// A bare TCP client for the tests: sends bytes exactly as given (HTTP libraries would normalise
// "/../x" or refuse to send one byte at a time) and reads what the server answers.
#pragma once

#include <arpa/inet.h>
#include <poll.h>
#include <sys/socket.h>
#include <unistd.h>

#include <chrono>
#include <string>

namespace glint::testing {

class RawConnection {
public:
    explicit RawConnection(int port) : fd_(::socket(AF_INET, SOCK_STREAM, 0)) {
        sockaddr_in addr{};
        addr.sin_family = AF_INET;
        addr.sin_port = htons(uint16_t(port));
        addr.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
        connected_ = ::connect(fd_, reinterpret_cast<sockaddr*>(&addr), sizeof addr) == 0;
    }
    ~RawConnection() { ::close(fd_); }
    RawConnection(const RawConnection&) = delete;
    RawConnection& operator=(const RawConnection&) = delete;

    bool connected() const { return connected_; }
    // False once the server has closed its side (or the send failed).
    bool send(const std::string& bytes) {
        return connected_ && ::send(fd_, bytes.data(), bytes.size(), MSG_NOSIGNAL) == ssize_t(bytes.size());
    }
    // Whether the server has sent something (or closed) by now.
    bool answered() const {
        pollfd p{fd_, POLLIN, 0};
        return ::poll(&p, 1, 0) > 0;
    }
    // What the server sends until it closes the connection, or until `timeout` passes (then
    // `closed()` stays false).
    std::string read_until_closed(std::chrono::milliseconds timeout) { return read(timeout, ""); }
    // What the server sends until the response headers are complete.
    std::string read_headers(std::chrono::milliseconds timeout) { return read(timeout, "\r\n\r\n"); }
    bool closed() const { return closed_; }

private:
    std::string read(std::chrono::milliseconds timeout, const std::string& stop) {
        std::string received;
        const auto end = std::chrono::steady_clock::now() + timeout;
        while (stop.empty() || received.find(stop) == std::string::npos) {
            const auto left = std::chrono::duration_cast<std::chrono::milliseconds>(end - std::chrono::steady_clock::now());
            pollfd p{fd_, POLLIN, 0};
            if (left.count() <= 0 || ::poll(&p, 1, int(left.count())) <= 0) break;
            char buffer[4096];
            const ssize_t n = ::recv(fd_, buffer, sizeof buffer, 0);
            if (n <= 0) {
                closed_ = true;
                break;
            }
            received.append(buffer, size_t(n));
        }
        return received;
    }

    int fd_;
    bool connected_ = false, closed_ = false;
};

// The status code of a raw response ("HTTP/1.1 403 Forbidden..." -> 403), or 0.
inline int status_of(const std::string& response) {
    return response.starts_with("HTTP/1.1 ") && response.size() >= 12 ? std::stoi(response.substr(9, 3)) : 0;
}
// The body of a raw response (after the blank line).
inline std::string body_of(const std::string& response) {
    const size_t start = response.find("\r\n\r\n");
    return start == std::string::npos ? "" : response.substr(start + 4);
}

}  // namespace glint::testing
