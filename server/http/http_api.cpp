#include "http/http_api.h"

#include <chrono>

#include <spdlog/spdlog.h>

#include "base/files.h"
#include "http/auth.h"
#include "http/error_response.h"
#include "http/guarded_server.h"
#include "http/job_images.h"
#include "http/job_patch.h"
#include "http/job_request.h"
#include "http/job_view.h"
#include "http/static_files.h"

namespace glint {
namespace {

using namespace std::chrono_literals;
using Clock = std::chrono::steady_clock;
constexpr auto kPoll = 250ms;  // how often a waiting stream looks at its client and the job
constexpr auto kPing = 15s;    // SSE comment that keeps proxies from closing an idle stream

void send_json(httplib::Response& res, const nlohmann::json& body, int status = 200) {
    res.status = status;
    res.set_content(body.dump(), "application/json");
}

bool write(httplib::DataSink& sink, const std::string& text) { return sink.write(text.data(), text.size()); }

thread_local Clock::time_point t_request_start;

// Reasons for the statuses cpp-httplib answers by itself, before any handler runs.
std::string reason(int status) {
    switch (status) {
        case 400: return "bad request";
        case 404: return "no such route or file";
        case 405: return "method not allowed";
        case 413: return "request body too large";
        case 414: return "URI too long";
        case 416: return "range not satisfiable";
        default: return "HTTP " + std::to_string(status);
    }
}

}  // namespace

HttpApi::HttpApi(JobManager& jobs, ThreadPool& pool, AssetCache& assets, const ServiceConfig& service,
                 HttpConfig config)
    : jobs_(jobs),
      pool_(pool),
      assets_(assets),
      scenes_(service.scenes),
      scene_limits_(service.scene),
      config_(std::move(config)) {}

std::shared_ptr<Job> HttpApi::job_or_404(const httplib::Request& req, httplib::Response& res) const {
    auto job = jobs_.find(req.matches[1]);
    if (!job) send_error(res, 404, "no job " + std::string(req.matches[1]));
    return job;
}

// Parses and queues the job a request describes, or answers with the error and returns null.
std::shared_ptr<Job> HttpApi::accept(const httplib::Request& req, httplib::Response& res) {
    try {
        return jobs_.submit(parse_job_request(req.body, scenes_, scene_limits_, &assets_), req.body);
    } catch (const ServiceError& e) {
        send_error(res, e);
    }
    return nullptr;
}

void HttpApi::submit(const httplib::Request& req, httplib::Response& res) {
    if (auto job = accept(req, res)) {
        res.set_header("Location", job_url(job->id()));
        send_json(res, job_status(*job), 202);
    }
}

// {"priority": n}: a queued job moves in the queue, a running one changes its share of the
// render threads at once; an ended job has nothing left to change (409).
void HttpApi::patch(const httplib::Request& req, httplib::Response& res) {
    auto job = job_or_404(req, res);
    if (!job) return;
    try {
        const JobPatch patch = parse_job_patch(req.body);
        if (patch.priority && !job->set_priority(*patch.priority))
            return send_error(res, 409, "the job has ended: its priority no longer matters");
        send_json(res, job_status(*job));
    } catch (const ServiceError& e) {
        send_error(res, e);
    }
}

// The plain `curl --data @scene.json .../render -o out.png` use: the finished PNG. Sent chunked
// once the job ends; a client that goes away cancels its job.
void HttpApi::render(const httplib::Request& req, httplib::Response& res) {
    auto job = accept(req, res);
    if (!job) return;
    res.set_header("X-Glint-Job", job->id());
    res.set_chunked_content_provider("image/png", [job](size_t, httplib::DataSink& sink) {
        if (!sink.is_writable()) {
            job->cancel();
            return false;
        }
        const JobSnapshot s = job->wait(UINT64_MAX, kPoll);
        if (!is_final(s.state)) return true;
        if (!s.png) return false;
        sink.write(reinterpret_cast<const char*>(s.png->data()), s.png->size());
        sink.done();
        return true;
    });
}

// Streams are capped in total (503: the server is busy) and per remote address (429: this
// client holds too many). Every admitted stream is released by its response's releaser.
bool HttpApi::admit_stream(const httplib::Request& req, httplib::Response& res) {
    if (++open_streams_ > config_.max_streams) {
        --open_streams_;
        res.set_header("Retry-After", "5");
        send_error(res, 503, "too many open streams (limit " + std::to_string(config_.max_streams) + ")");
        return false;
    }
    std::lock_guard lock(clients_mutex_);
    size_t& mine = streams_by_client_[req.remote_addr];
    if (mine >= config_.streams_per_client) {
        --open_streams_;
        if (mine == 0) streams_by_client_.erase(req.remote_addr);
        res.set_header("Retry-After", "5");
        send_error(res, 429, "too many open streams from " + req.remote_addr + " (limit " +
                                 std::to_string(config_.streams_per_client) + " per client)");
        return false;
    }
    ++mine;
    res.set_header("Cache-Control", "no-cache");
    return true;
}

void HttpApi::release_stream(const std::string& client) {
    --open_streams_;
    std::lock_guard lock(clients_mutex_);
    const auto it = streams_by_client_.find(client);
    if (it != streams_by_client_.end() && --it->second == 0) streams_by_client_.erase(it);
}

// multipart/x-mixed-replace: one PNG part per finished pass (the latest frame wins, none is
// queued), then the closing boundary once the job has ended.
void HttpApi::stream(const Request& req, Response& res) {
    const auto job = job_or_404(req, res);
    if (!job || !admit_stream(req, res)) return;
    res.set_chunked_content_provider(
        "multipart/x-mixed-replace; boundary=frame",
        [this, job, sent = uint64_t(0)](size_t, httplib::DataSink& sink) mutable {
            if (!sink.is_writable()) return false;
            const JobSnapshot s = job->wait(sent, kPoll);
            if (s.frame > sent && s.png) {
                const std::string head = "--frame\r\nContent-Type: image/png\r\nContent-Length: " +
                                         std::to_string(s.png->size()) + "\r\n\r\n";
                if (!write(sink, head) || !sink.write(reinterpret_cast<const char*>(s.png->data()), s.png->size()) ||
                    !write(sink, "\r\n"))
                    return false;
                sent = s.frame;
            }
            if ((is_final(s.state) && s.frame == sent) || stopping_) {
                write(sink, "--frame--\r\n");
                sink.done();
            }
            return true;
        },
        [this, client = req.remote_addr](bool) { release_stream(client); });
}

// Server-Sent Events: the job's status after every pass, then a final `done` event.
void HttpApi::events(const Request& req, Response& res) {
    const auto job = job_or_404(req, res);
    if (!job || !admit_stream(req, res)) return;
    res.set_chunked_content_provider(
        "text/event-stream",
        [this, job, sent = uint64_t(0), last_write = Clock::now()](size_t, httplib::DataSink& sink) mutable {
            if (!sink.is_writable()) return false;
            const JobSnapshot s = job->wait(sent, kPoll);
            const bool final = is_final(s.state) || stopping_;
            if (s.frame > sent || final) {
                sent = s.frame;
                last_write = Clock::now();
                if (!write(sink, "id: " + std::to_string(s.frame) + "\nevent: " + (final ? "done" : "progress") +
                                     "\ndata: " + job_status(*job).dump() + "\n\n"))
                    return false;
                if (final) sink.done();
            } else if (Clock::now() - last_write > kPing) {
                last_write = Clock::now();
                return write(sink, ": ping\n\n");
            }
            return true;
        },
        [this, client = req.remote_addr](bool) { release_stream(client); });
}

void HttpApi::install(httplib::Server& server) {
    install_limits(server);
    install_hooks(server);
    install_routes(server);
}

void HttpApi::install_limits(httplib::Server& server) const {
    server.set_payload_max_length(config_.max_body_bytes);
    server.set_read_timeout(10, 0);
    server.set_write_timeout(30, 0);
    server.set_keep_alive_max_count(5);
    server.set_keep_alive_timeout(5);
    server.set_tcp_nodelay(true);  // small JSON replies must not wait for delayed ACKs (Nagle)
}

// The token check before routing, request logging, and a JSON body for every error, also those
// cpp-httplib answers itself (404, 413, ...) and exceptions out of a handler (500).
void HttpApi::install_hooks(httplib::Server& server) {
    server.set_pre_routing_handler([this](const httplib::Request& req, httplib::Response& res) {
        t_request_start = Clock::now();
        const std::string refusal = check_token(req, config_.token);
        if (refusal.empty()) return httplib::Server::HandlerResponse::Unhandled;
        res.set_header("WWW-Authenticate", "Bearer");
        res.set_header("Connection", "close");  // its body, if any, was never read
        GuardedServer::close_after_response();
        send_error(res, 401, refusal);
        return httplib::Server::HandlerResponse::Handled;
    });
    server.set_logger([](const httplib::Request& req, const httplib::Response& res) {
        const double ms = std::chrono::duration<double, std::milli>(Clock::now() - t_request_start).count();
        spdlog::info("{} {} {} {}B {:.1f}ms", req.method, req.path, res.status, res.body.size(), ms);
    });
    server.set_error_handler(httplib::Server::HandlerWithResponse(
        [request_timeout = config_.request_timeout](const httplib::Request&, httplib::Response& res) {
            if (GuardedServer::request_timed_out()) {
                res.set_header("Connection", "close");  // GuardedServer closes it
                send_error(res, 408,
                           "request not received within " +
                               std::to_string(request_timeout.count()) + " ms");
            } else if (res.body.empty()) {
                send_error(res, res.status, reason(res.status));
            } else {
                return httplib::Server::HandlerResponse::Unhandled;
            }
            return httplib::Server::HandlerResponse::Handled;
        }));
    server.set_exception_handler([](const httplib::Request&, httplib::Response& res, std::exception_ptr e) {
        std::string what = "internal error";
        try {
            std::rethrow_exception(e);
        } catch (const std::exception& ex) {
            what = ex.what();
        } catch (...) {
        }
        spdlog::error("request failed: {}", what);
        send_error(res, 500, what);
    });
}

void HttpApi::install_routes(httplib::Server& server) {
    if (!std::filesystem::is_directory(config_.web))
        spdlog::warn("web folder {} not found: the page is not served", config_.web.string());
    for (const Route& route : routes()) {
        const std::string pattern = path_pattern(route);
        httplib::Server::Handler handler = [this, &route](const Request& req, Response& res) {
            route.handler(*this, req, res);
        };
        switch (route.method) {
            case Method::get: server.Get(pattern, std::move(handler)); break;
            case Method::post: server.Post(pattern, std::move(handler)); break;
            case Method::patch: server.Patch(pattern, std::move(handler)); break;
            case Method::delete_: server.Delete(pattern, std::move(handler)); break;
        }
    }
}

void HttpApi::list_jobs(const Request&, Response& res) {
    nlohmann::json list = nlohmann::json::array();
    for (const auto& job : jobs_.list()) list.push_back(job_status(*job));
    send_json(res, list);
}

void HttpApi::show_job(const Request& req, Response& res) {
    if (auto job = job_or_404(req, res)) send_json(res, job_status(*job));
}

void HttpApi::cancel(const Request& req, Response& res) {
    if (auto job = job_or_404(req, res)) {
        job->cancel();
        send_json(res, job_status(*job));
    }
}

// Whatever the image, an unknown job is 404 and one without a finished pass yet 409.
void HttpApi::image(const Request& req, Response& res, const JobImage& image) {
    const auto job = job_or_404(req, res);
    if (!job) return;
    try {
        const JobSnapshot snapshot = job->snapshot();
        const ImageContent content = image.make({*job, snapshot, jobs_.denoise_gate()});
        if (!content.bytes) return send_error(res, 409, "no pass has finished yet");
        for (const auto& [name, value] : content.headers) res.set_header(name, value);
        res.set_content(reinterpret_cast<const char*>(content.bytes->data()), content.bytes->size(), image.content_type);
    } catch (const ServiceError& e) {
        send_error(res, e);
    }
}

void HttpApi::presets(const Request&, Response& res) { send_json(res, list_presets(scenes_)); }

void HttpApi::preset(const Request& req, Response& res) {
    const auto file = preset_path(scenes_, req.matches[1]);
    if (file.empty()) return send_error(res, 404, "no preset " + std::string(req.matches[1]));
    const std::vector<uint8_t> text = read_file(file.string(), size_t(16) << 20);
    res.set_content(reinterpret_cast<const char*>(text.data()), text.size(), "application/json");
}

void HttpApi::health(const Request&, Response& res) {
    send_json(res, {{"status", "ok"},
                    {"jobs_running", jobs_.running()},
                    {"jobs_queued", jobs_.queued()},
                    {"open_streams", open_streams_.load()},
                    {"render_threads", pool_.size()},
                    {"render_batches_waiting", pool_.pending_batches()}});
}

void HttpApi::page(const Request& req, Response& res) { serve_static_file(config_.web, req, res); }

}  // namespace glint
