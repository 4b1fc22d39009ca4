// The one time base of the sans-I/O protocol core: machines are told "now", never read a clock.
#pragma once

#include <chrono>

namespace olcb {

/// Monotonic clock the programs feed into the state machines; tests use simulated time points.
using Clock = std::chrono::steady_clock;
/// A point in time as the state machines see it.
using TimePoint = Clock::time_point;
/// A span of time as the state machines see it.
using Duration = Clock::duration;

}  // namespace olcb
