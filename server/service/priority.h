// A job's priority: an integer from kMinPriority to kMaxPriority, 0 unless a client sets it
// (PATCH /jobs/{id}, http/job_patch.h).
#pragma once

#include <cmath>

namespace glint {

inline constexpr int kMinPriority = -10;
inline constexpr int kMaxPriority = 10;

// A job's weight when running jobs share the render threads: each step of priority doubles its
// share, so a step means the same wherever it is taken and [-10, 10] spans shares of about a
// million to one, with no weight ever 0 (a job never starves) or overflowing.
inline double priority_weight(int priority) { return std::ldexp(1.0, priority); }

}  // namespace glint
