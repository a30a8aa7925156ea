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

JobState job_state_named(const std::string& name) {
    for (JobState s : {JobState::queued, JobState::running, JobState::done, JobState::cancelled,
                       JobState::failed})
        if (name == to_string(s)) return s;
    throw std::invalid_argument("unknown state \"" + name + "\"");
}

}  // namespace glint
