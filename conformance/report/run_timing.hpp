// The answer and silence windows of one node's run, derived from the node's measured answer
// latency so a slow node or a busy segment is not blamed for the tool's impatience.
#pragma once

#include <chrono>
#include <optional>
#include <string>
#include <vector>

#include "base/timings.hpp"
#include "openlcb/clock.hpp"

namespace olcb::conform {

/// Windows of one node's run (docs/checks.md "Timing").
struct RunTiming {
    std::optional<Duration> latency;                    ///< median Verify round trip
    Duration worst{};                                   ///< slowest round trip measured
    double scale = 1.0;                                 ///< --timeout-scale
    Duration silence = std::chrono::milliseconds(250);  ///< silence awaited this long
    Duration answer = std::chrono::seconds(1);          ///< longest wait for an owed answer
    Duration reply = base::kRequesterTimeout;           ///< reply datagram after its OK
    Duration quiet = std::chrono::milliseconds(1200);   ///< span of message.no-unsolicited

    /// "latency 2 ms (worst 3 ms); windows: silence 250 ms, answers 1000 ms, ..." for the report.
    std::string describe() const;
};

/// Windows from round-trip samples (empty: the fixed floors), each above its floor, times scale.
RunTiming derive_timing(std::vector<Duration> samples, double scale);

}  // namespace olcb::conform
