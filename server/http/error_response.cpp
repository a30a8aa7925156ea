#include "http/error_response.h"

#include <nlohmann/json.hpp>

namespace glint {
namespace {

int status_of(ServiceError::Kind kind) {
    switch (kind) {
        case ServiceError::Kind::malformed: return 400;
        case ServiceError::Kind::invalid: return 422;
        case ServiceError::Kind::not_found: return 404;
        case ServiceError::Kind::busy: return 429;
    }
    return 500;
}

}  // namespace

void send_error(httplib::Response& res, int status, const std::string& message,
                const std::string& path) {
    res.status = status;
    nlohmann::json body = {{"error", message}};
    if (!path.empty()) body["path"] = path;
    res.set_content(body.dump(), "application/json");
}

void send_error(httplib::Response& res, const ServiceError& error) {
    if (error.kind() == ServiceError::Kind::busy) res.set_header("Retry-After", "5");  // seconds
    send_error(res, status_of(error.kind()), error.what(), error.path());
}

}  // namespace glint
