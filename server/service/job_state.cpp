#include "service/job_state.h"

#include <stdexcept>
#include <string>

namespace glint {

const char* to_string(JobState state) {
    switch (state) {
        case JobState::queued: return "queued";
        case JobState::running: return "running";
        case JobState::done: return "done";
        case JobState::cancelled: return "cancelled";
        case JobState::failed: return "failed";
    }
    return "?";
}

bool can_move(JobState from, JobState to) {
    if (is_final(from)) return false;
    return from == to || from == JobState::queued || is_final(to);
}

JobState job_state_named(const std::string& name) {
    for (JobState s : {JobState::queued, JobState::running, JobState::done, JobState::cancelled,
                       JobState::failed})
        if (name == to_string(s)) return s;
    throw std::invalid_argument("unknown state \"" + name + "\"");
}

const char* stop_reason_name(StopReason reason) {
    switch (reason) {
        case StopReason::completed: return "spp";
        case StopReason::time_limit: return "time_limit";
        case StopReason::target_error: return "target_error";
        case StopReason::cancelled: return "cancelled";
    }
    return "?";
}

StopReason stop_reason_named(const std::string& name) {
    for (StopReason r : {StopReason::completed, StopReason::time_limit, StopReason::target_error, StopReason::cancelled})
        if (name == stop_reason_name(r)) return r;
    throw std::invalid_argument("unknown stop reason \"" + name + "\"");
}

}  // namespace glint
