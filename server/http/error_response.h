// JSON error bodies, {"error": MESSAGE, "path": JSON_PATH}, and the one place that says which
// HTTP status each of the service's errors (service/errors.h) is.
#pragma once

#include <string>

#include <httplib.h>

#include "service/errors.h"

namespace glint {

void send_error(httplib::Response& res, int status, const std::string& message,
                const std::string& path = "");
// 400 malformed, 422 invalid, 404 not found, 429 busy (with Retry-After).
void send_error(httplib::Response& res, const ServiceError& error);

}  // namespace glint
