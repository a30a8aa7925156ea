#include "http/job_view.h"

#include "service/progress_json.h"

namespace glint {

std::string job_url(const std::string& id) { return "/jobs/" + id; }

nlohmann::json job_status(const Job& job) {
    const JobSnapshot s = job.snapshot();
    const Progress& p = s.progress;
    const double eta = s.state == JobState::running ? eta_seconds(p) : 0;
    const std::string self = job_url(job.id());
    nlohmann::json j = progress_json(p);
    j.update({
        {"id", job.id()},
        {"state", to_string(s.state)},
        {"width", job.settings().width},
        {"height", job.settings().height},
        {"eta", eta},
        {"frame", s.frame},
        {"urls",
         {{"self", self},
          {"png", self + "/image.png"},
          {"pfm", self + "/image.pfm"},
          {"stream", self + "/stream"},
          {"events", self + "/events"}}},
    });
    if (s.parts)
        j["parts"] = {{"queued", s.parts->queued}, {"running", s.parts->running}, {"done", s.parts->done},
                      {"requeued", s.parts->requeued}};
    if (!s.error.empty()) j["error"] = s.error;
    if (!job.warnings().empty()) j["warnings"] = job.warnings();
    return j;
}

}  // namespace glint
