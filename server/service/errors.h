// What the service refuses, in its own terms: it knows no HTTP. The HTTP layer turns each kind
// into a status in one place (http/error_response.cpp); other callers (the store's restore, the
// fuzz harness) read the message and the JSON path.
#pragma once

#include <stdexcept>
#include <string>

namespace glint {

class ServiceError : public std::runtime_error {
public:
    enum class Kind {
        malformed,  // the request is not JSON a job can be read from (syntax, nesting)
        invalid,    // the JSON is fine, but a field is wrong or over a limit
        not_found,  // it names something that does not exist (a preset)
        busy,       // the service takes no more work now (queue full, shutting down): try later
    };
    ServiceError(Kind kind, const std::string& message, const std::string& path = "")
        : std::runtime_error(message), kind_(kind), path_(path) {}
    Kind kind() const { return kind_; }
    // The JSON path of the offending field ("spp", "objects[0].radius"); empty if none.
    const std::string& path() const { return path_; }

private:
    Kind kind_;
    std::string path_;
};

struct MalformedRequest : ServiceError {
    explicit MalformedRequest(const std::string& message, const std::string& path = "")
        : ServiceError(Kind::malformed, message, path) {}
};

struct InvalidRequest : ServiceError {
    explicit InvalidRequest(const std::string& message, const std::string& path = "")
        : ServiceError(Kind::invalid, message, path) {}
};

struct NotFound : ServiceError {
    explicit NotFound(const std::string& message, const std::string& path = "")
        : ServiceError(Kind::not_found, message, path) {}
};

struct Busy : ServiceError {
    explicit Busy(const std::string& message) : ServiceError(Kind::busy, message) {}
};

}  // namespace glint
