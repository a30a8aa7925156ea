// The web page's files, from one folder and nothing outside it: no "..", no absolute or
// encoded paths (cpp-httplib has decoded %2e and %2f before this sees them), no symlinks that
// lead out. cpp-httplib's own mount point follows symlinks, so glint serves the folder itself.
#pragma once

#include <filesystem>

#include <httplib.h>

namespace glint {

void serve_static_file(const std::filesystem::path& root, const httplib::Request& req, httplib::Response& res);

}  // namespace glint
