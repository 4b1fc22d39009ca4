// The Broadcast Time checks (conformance/checks/broadcast_time.cpp) against simulated clocks: a
// generator passes every generator check and is put back as it was, a consumer every consumer
// check, a node without clocks SKIPs them all, and each clock fault is caught by its check.
#include <gtest/gtest.h>

#include <chrono>
#include <string>
#include <vector>

#include "conformance/checks/protocol_checks.hpp"
#include "conformance/sim_bench.hpp"
#include "simnode/broadcast_clock.hpp"

namespace olcb::conform {
namespace {

using namespace std::chrono_literals;
using testing::contains;
using testing::dump;
using testing::expect_status;
using testing::SimBench;

constexpr const char* kGeneratorChecks[] = {"clock.identify-ranges",
                                            "clock.query",
                                            "clock.set-immediate",
                                            "clock.set-sync",
                                            "clock.set-once",
                                            "clock.set-effective",
                                            "clock.requested-minute",
                                            "clock.report-frequency",
                                            "clock.rate",
                                            "clock.rollover",
                                            "clock.startup",
                                            "clock.restored"};
constexpr const char* kConsumerChecks[] = {"clock.consumer-startup", "clock.consumer-sync",
                                           "clock.consumer-start-stop", "clock.consumer-rate"};

simnode::ClockConfig clock_of(const std::string& spec) {
    std::string error;
    auto c = simnode::parse_clock_config(spec, simnode::fast_time(2025, 1, 1, 0, 0), error);
    EXPECT_TRUE(c) << error;
    return c.value_or(simnode::ClockConfig{});
}

// A node running clocks (specs as the scenario key gives them) with faults.
std::unique_ptr<SimBench> clock_node(const std::vector<std::string>& specs,
                                     const std::vector<std::string>& faults = {}) {
    simnode::NodeConfig cfg;
    cfg.node_id = kDut;
    cfg.cdi = testing::default_cdi();
    for (const auto& s : specs) cfg.clocks.push_back(clock_of(s));
    std::string error;
    auto fs = simnode::parse_faults(faults, error);
    EXPECT_TRUE(fs) << error;
    if (fs) cfg.faults = *fs;
    auto b = SimBench::serve(cfg, error);
    EXPECT_TRUE(b) << error;
    return b;
}

struct Options {
    bool named = true;
    bool reboot = true;
    bool read_only = false;
    std::vector<std::string> only = {"clock.*"};
};

std::vector<CheckResult> clock_checks(SimBench& b, const Options& o = {}) {
    auto node = b.start();
    if (!node) return {};
    ProtocolOptions po;
    po.named = o.named;
    po.reboot = o.reboot;
    po.read_only = o.read_only;
    po.selection.only = o.only;
    CheckContext ctx;
    return run_protocol_checks(*b.session, *node, po, ctx);
}

TEST(BroadcastTimeChecks, AGeneratorPassesEveryGeneratorCheckAndIsPutBack) {
    auto b = clock_node({"generator default-fast rate=60 time=1955-07-04T06:00"});
    ASSERT_TRUE(b);
    const TimePoint began = b->net.now();
    const auto results = clock_checks(*b);
    for (const char* id : kGeneratorChecks) expect_status(results, id, Status::kPass);
    for (const char* id : kConsumerChecks) {
        const auto& r = expect_status(results, id, Status::kSkip);
        EXPECT_TRUE(contains(r.message, "not a Broadcast Time clock consumer")) << r.message;
    }
    for (const auto& r : results) EXPECT_EQ(r.category, Category::kClock) << r.id;
    // Put back: running at 60.00, the time it would show had nothing been set (to the minute).
    const simnode::BroadcastClock& clock = b->dut->clocks().front();
    EXPECT_TRUE(clock.running());
    EXPECT_EQ(clock.rate_quarters(), 240);
    const auto elapsed =
        std::chrono::duration_cast<std::chrono::microseconds>(b->net.now() - began);
    const auto want = simnode::fast_time(1955, 7, 4, 6, 0) + elapsed * 60;
    const auto got = clock.time_at(b->net.now());
    EXPECT_LT(got > want ? got - want : want - got, 2min) << simnode::fast_time_text(got);
    // Seconds of simulated time, not minutes.
    EXPECT_LT(b->net.now() - began, 40s);
}

TEST(BroadcastTimeChecks, WithoutNodeOnlyTheChecksThatSetNothingRun) {
    auto b = clock_node({"generator default-fast rate=1 time=1955-07-04T06:00"});
    ASSERT_TRUE(b);
    const auto results = clock_checks(*b, {false, false, false});
    expect_status(results, "clock.identify-ranges", Status::kPass);
    const auto& q = expect_status(results, "clock.query", Status::kPass);
    // At 1.00 the next minute may be a minute away: not awaited without --thorough.
    EXPECT_TRUE(contains(q.message, "item 6 not awaited")) << q.message;
    const auto& set = expect_status(results, "clock.set-sync", Status::kSkip);
    EXPECT_TRUE(contains(set.message, "--node")) << set.message;
    expect_status(results, "clock.startup", Status::kSkip);
    EXPECT_TRUE(b->dut->clocks().front().subscribed().empty());
}

TEST(BroadcastTimeChecks, RestoredJudgesOnlyTheSessionsTheSelectionMade) {
    auto b = clock_node({"generator default-fast rate=60 time=1955-07-04T06:00"});
    ASSERT_TRUE(b);
    // Alone it makes the Set exchange; with the midnight checks, the run's session only.
    auto results = clock_checks(*b, {.only = {"clock.restored"}});
    const auto& alone = expect_status(results, "clock.restored", Status::kPass);
    EXPECT_TRUE(contains(alone.message, "after the Set exchange")) << alone.message;
    EXPECT_FALSE(contains(alone.message, "midnight")) << alone.message;
    results = clock_checks(*b, {.only = {"clock.rollover", "clock.restored"}});
    const auto& run = expect_status(results, "clock.restored", Status::kPass);
    EXPECT_TRUE(contains(run.message, "after the run through midnight")) << run.message;
    EXPECT_FALSE(contains(run.message, "Set exchange")) << run.message;
}

TEST(BroadcastTimeChecks, ReadOnlySetsNothing) {
    auto b = clock_node({"generator default-fast rate=60"});
    ASSERT_TRUE(b);
    const auto results = clock_checks(*b, {true, false, true});
    const auto& r = expect_status(results, "clock.rollover", Status::kSkip);
    EXPECT_TRUE(contains(r.message, "--read-only")) << r.message;
}

TEST(BroadcastTimeChecks, ANodeWithoutClocksSkipsThemAll) {
    SimBench b;
    const auto results = clock_checks(b);
    for (const char* id : kGeneratorChecks) {
        const auto& r = expect_status(results, id, Status::kSkip);
        EXPECT_TRUE(contains(r.message, "not a Broadcast Time clock generator")) << r.message;
    }
    for (const char* id : kConsumerChecks) expect_status(results, id, Status::kSkip);
}

TEST(BroadcastTimeChecks, AStoppedClockOwesNoSixthItem) {
    auto b = clock_node({"generator alternate-2 rate=4 time=2001-02-03T04:05 stopped"});
    ASSERT_TRUE(b);
    const auto results = clock_checks(*b, {false, false, false});
    const auto& q = expect_status(results, "clock.query", Status::kPass);
    EXPECT_TRUE(contains(q.message, "Stop, Report Rate 4.00, Report Year 2001")) << q.message;
}

TEST(BroadcastTimeChecks, EveryClockOfANodeIsJudged) {
    auto b = clock_node({"generator default-fast rate=60", "generator alternate-1 rate=120"},
                        {"clock-query-ignored"});
    ASSERT_TRUE(b);
    const auto results = clock_checks(*b, {false, false, false});
    const auto& q = expect_status(results, "clock.query", Status::kFail);
    EXPECT_EQ(q.details.size(), 2u) << dump(results);
}

TEST(BroadcastTimeChecks, AConsumerPassesEveryConsumerCheck) {
    auto b = clock_node({"consumer default-realtime"});
    ASSERT_TRUE(b);
    const auto results = clock_checks(*b);
    for (const char* id : kConsumerChecks) expect_status(results, id, Status::kPass);
    expect_status(results, "clock.query", Status::kSkip);
}

TEST(BroadcastTimeChecks, AHalfConsumerRangeWarnsWhenIdentified) {
    auto b = clock_node({"generator default-fast rate=60"}, {"clock-half-range"});
    ASSERT_TRUE(b);
    const auto results = clock_checks(*b, {false, false, false});
    const auto& r = expect_status(results, "clock.identify-ranges", Status::kWarn);
    EXPECT_TRUE(contains(r.message, "01.01.00.00.01.00.FF.FF")) << r.message;
    // The ranges it did identify, so the reader sees which half is missing.
    EXPECT_TRUE(contains(r.message, "Consumer Range Identified 01.01.00.00.01.00.80.00"))
        << r.message;
}

struct FaultCase {
    const char* fault;
    const char* check;
};

class BroadcastTimeFault : public ::testing::TestWithParam<FaultCase> {};

TEST_P(BroadcastTimeFault, IsCaughtByItsCheck) {
    auto b =
        clock_node({"generator default-fast rate=60 time=1955-07-04T06:00"}, {GetParam().fault});
    ASSERT_TRUE(b);
    const auto results = clock_checks(*b);
    expect_status(results, GetParam().check, Status::kFail);
}

INSTANTIATE_TEST_SUITE_P(Faults, BroadcastTimeFault,
                         ::testing::Values(FaultCase{"clock-drift", "clock.rate"},
                                           FaultCase{"clock-drift=10", "clock.rate"},
                                           FaultCase{"clock-rollover-wrong", "clock.rollover"},
                                           FaultCase{"clock-rollover-wrong=date", "clock.rollover"},
                                           FaultCase{"clock-rollover-wrong=late", "clock.rollover"},
                                           FaultCase{"clock-query-ignored", "clock.query"},
                                           FaultCase{"clock-sync-order", "clock.query"},
                                           FaultCase{"clock-sync-order", "clock.set-sync"},
                                           FaultCase{"clock-half-range", "clock.startup"},
                                           FaultCase{"clock-reports-asked", "clock.set-effective"}),
                         [](const auto& test) {
                             std::string name =
                                 std::string(test.param.fault) + "_" + test.param.check;
                             for (char& c : name)
                                 if (c == '-' || c == '.' || c == '=') c = '_';
                             return name;
                         });

}  // namespace
}  // namespace olcb::conform
