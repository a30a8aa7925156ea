#include "http/static_files.h"

#include "base/files.h"
#include "http/error_response.h"

namespace glint {
namespace {

std::string content_type(const std::filesystem::path& file) {
    const std::string ext = file.extension().string();
    if (ext == ".html") return "text/html";
    if (ext == ".js" || ext == ".mjs") return "text/javascript";
    if (ext == ".css") return "text/css";
    if (ext == ".json") return "application/json";
    if (ext == ".png") return "image/png";
    if (ext == ".svg") return "image/svg+xml";
    if (ext == ".ico") return "image/x-icon";
    if (ext == ".txt" || ext == ".md") return "text/plain";
    return "application/octet-stream";
}

}  // namespace

void serve_static_file(const std::filesystem::path& root, const httplib::Request& req, httplib::Response& res) {
    std::string relative = req.path.substr(1);  // the route only matches paths that start with '/'
    if (relative.empty() || relative.ends_with('/')) relative += "index.html";
    const auto resolved = resolve_inside(root, relative);
    if (!resolved) return send_error(res, 403, "path leaves the web folder");
    std::filesystem::path file = *resolved;
    std::error_code error;
    if (std::filesystem::is_directory(file, error)) file /= "index.html";
    if (!std::filesystem::is_regular_file(file, error)) return send_error(res, 404, "no such route or file");
    const std::vector<uint8_t> bytes = read_file(file.string(), size_t(16) << 20);
    res.set_content(reinterpret_cast<const char*>(bytes.data()), bytes.size(), content_type(file).c_str());
}

}  // namespace glint
