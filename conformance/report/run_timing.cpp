#include "conformance/report/run_timing.hpp"

#include <algorithm>

namespace olcb::conform {
namespace {

// Multiples of the slowest round trip each window allows before it gives up (or decides a
// node is silent); the floors are the windows a fast node on an idle bus gets.
constexpr int kSilenceRoundTrips = 4;
constexpr int kAnswerRoundTrips = 10;

long long ms(Duration d) {
    return std::chrono::duration_cast<std::chrono::milliseconds>(d).count();
}

Duration scaled(Duration floor, Duration derived, double scale) {
    const auto longest = std::max(floor, derived);
    return std::chrono::duration_cast<Duration>(longest * scale);
}

}  // namespace

RunTiming derive_timing(std::vector<Duration> samples, double scale) {
    RunTiming t;
    t.scale = scale > 0 ? scale : 1.0;
    const RunTiming floors;
    if (!samples.empty()) {
        std::sort(samples.begin(), samples.end());
        t.latency = samples[samples.size() / 2];
        t.worst = samples.back();
    }
    t.silence = scaled(floors.silence, t.worst * kSilenceRoundTrips, t.scale);
    t.answer = scaled(floors.answer, t.worst * kAnswerRoundTrips, t.scale);
    t.reply = scaled(floors.reply, t.worst * kAnswerRoundTrips, t.scale);
    t.quiet = scaled(floors.quiet, t.silence, 1.0);
    return t;
}

std::string RunTiming::describe() const {
    std::string s = latency ? "latency " + std::to_string(ms(*latency)) + " ms (worst " +
                                  std::to_string(ms(worst)) + " ms)"
                            : "latency not measured";
    s += "; windows: silence " + std::to_string(ms(silence)) + " ms, answers " +
         std::to_string(ms(answer)) + " ms, replies " + std::to_string(ms(reply)) + " ms, quiet " +
         std::to_string(ms(quiet)) + " ms";
    if (scale != 1.0) s += " (--timeout-scale " + std::to_string(scale).substr(0, 4) + ")";
    return s;
}

}  // namespace olcb::conform
