// A job's priority: which queued job starts first, and its share of the render threads while
// it runs beside others.
#pragma once

#include <cmath>

namespace glint {

// Priorities a job may have; 0 is the default.
inline constexpr int kMinPriority = -10, kMaxPriority = 10;

// A running job's weight in the render pool's turns (base/thread_pool.h): each step of priority
// doubles its share of the tiles against a job one step below. Every weight is above zero, so
// a job at the lowest priority beside one at the highest still gets one turn in 2^20: slow, but
// never starved.
inline double priority_weight(int priority) { return std::ldexp(1.0, priority); }

}  // namespace glint
