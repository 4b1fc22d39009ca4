// The run's time windows: floors for a fast node, multiples of the slowest round trip otherwise,
// all scaled by --timeout-scale.
#include "conformance/report/run_timing.hpp"

#include <gtest/gtest.h>

#include <chrono>
#include <string>

namespace olcb::conform {
namespace {

using std::chrono::milliseconds;

TEST(RunTiming, FloorsForAFastNodeAndMultiplesOfTheSlowestRoundTrip) {
    const RunTiming fast = derive_timing({milliseconds(1), milliseconds(2)}, 1.0);
    EXPECT_EQ(fast.silence, milliseconds(250));
    EXPECT_EQ(fast.answer, std::chrono::seconds(1));
    EXPECT_EQ(fast.reply, std::chrono::seconds(3));
    const RunTiming slow =
        derive_timing({milliseconds(300), milliseconds(320), milliseconds(900)}, 1.0);
    EXPECT_EQ(*slow.latency, milliseconds(320));
    EXPECT_EQ(slow.worst, milliseconds(900));
    EXPECT_EQ(slow.silence, milliseconds(3600));
    EXPECT_EQ(slow.answer, milliseconds(9000));
    EXPECT_EQ(slow.quiet, milliseconds(3600));
    const RunTiming scaled = derive_timing({}, 2.0);
    EXPECT_FALSE(scaled.latency);
    EXPECT_EQ(scaled.silence, milliseconds(500));
    EXPECT_NE(scaled.describe().find("--timeout-scale 2"), std::string::npos) << scaled.describe();
}

}  // namespace
}  // namespace olcb::conform
