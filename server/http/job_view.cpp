#include "http/job_view.h"

#include <chrono>

#include "http/routes.h"
#include "service/job_state.h"
#include "service/progress_json.h"

namespace glint {

namespace {

// The URL of each route the table names for a job's status.
nlohmann::json job_urls(const Job& job) {
    nlohmann::json urls = nlohmann::json::object();
    for (const Route& route : routes()) {
        const StatusUrl& url = route.url;
        if (!url.name.empty() && (url.listed_for == StatusUrl::For::every_job || job.settings().adaptive.on()))
            urls[url.name] = route_url(route, job.id());
    }
    return urls;
}

}  // namespace

std::string job_url(const std::string& id) { return "/jobs/" + id; }

nlohmann::json job_status(const Job& job) {
    const JobSnapshot s = job.snapshot();
    const Progress& p = s.progress;
    const double eta = s.state == JobState::running ? eta_seconds(p) : 0;
    nlohmann::json j = progress_json(p);
    j.update({
        {"id", job.id()},
        {"state", to_string(s.state)},
        {"width", job.settings().width},
        {"height", job.settings().height},
        {"eta", eta},
        {"frame", s.frame},
        {"urls", job_urls(job)},
        {"priority", job.priority()},
        {"stop_reason", s.stop ? nlohmann::json(stop_reason_name(*s.stop)) : nlohmann::json()},
        {"time_limit", job.settings().time_limit},
        {"target_error", job.settings().target_error},
        {"created", std::chrono::duration<double>(job.created().time_since_epoch()).count()},
    });
    if (!job.settings().whole_image()) {
        const Region& r = job.settings().region;
        j["width"] = r.width();
        j["height"] = r.height();
        j["region"] = {{"x0", r.x0}, {"y0", r.y0}, {"x1", r.x1}, {"y1", r.y1},
                       {"full_width", job.settings().width}, {"full_height", job.settings().height}};
    }
    if (s.preview) j["preview"] = true;
    if (job.settings().adaptive.on()) {
        j["adaptive"] = {{"threshold", job.settings().adaptive.threshold}, {"min_spp", job.settings().adaptive.min_spp},
                         {"samples_max", s.samples_max}};
    }
    if (s.parts)
        j["parts"] = {{"queued", s.parts->queued}, {"running", s.parts->running}, {"done", s.parts->done},
                      {"requeued", s.parts->requeued}};
    if (!s.error.empty()) j["error"] = s.error;
    if (!job.warnings().empty()) j["warnings"] = job.warnings();
    return j;
}

}  // namespace glint
