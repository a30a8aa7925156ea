// Where a job is in its life, and where it may go from there. Apart from job.h so the store can
// record a state without knowing the job that has it.
#pragma once

#include <string>

#include "render/renderer.h"

namespace glint {

enum class JobState { queued, running, done, cancelled, failed };
const char* to_string(JobState state);
inline bool is_final(JobState s) {
    return s == JobState::done || s == JobState::cancelled || s == JobState::failed;
}
// The moves of a job's life: queued to any other state, running to a final one, and a state that
// is not final to itself (a running job's next frame). A final state never changes.
bool can_move(JobState from, JobState to);
// The state `name` names (to_string's inverse); throws std::invalid_argument for any other.
JobState job_state_named(const std::string& name);

// Why a job ended, as the API and the store name it: "spp" (it has every sample asked for),
// "time_limit", "target_error" or "cancelled".
const char* stop_reason_name(StopReason reason);
// stop_reason_name's inverse; throws std::invalid_argument for any other name.
StopReason stop_reason_named(const std::string& name);

}  // namespace glint
