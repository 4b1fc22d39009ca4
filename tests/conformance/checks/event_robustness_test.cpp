// The event robustness checks: PCERs with payload and Learn Event never upset the node.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "conformance/checks/check_registry.hpp"
#include "conformance/checks/check_run.hpp"
#include "conformance/checks/checks.hpp"
#include "conformance/checks_test_util.hpp"
#include "conformance/sim_bench.hpp"
#include "openlcb/can_defs.hpp"

namespace olcb::conform {
namespace {

using testing::expect_status;
using testing::SimBench;

TEST(EventRobustnessTest, DefaultAndIoBoardNodesTolerateBoth) {
    for (const char* file : {"default.xml", "io-board.xml"}) {
        SimBench b({}, read_text(std::filesystem::path(OLCB_SOURCE_DIR) / "scenarios" / file));
        auto node = b.start();
        ASSERT_TRUE(node) << file;
        CheckContext ctx;
        ProtocolOptions o;
        o.selection.thorough = true;  // Learn Event only then: a node in learn mode keeps it
        o.selection.only = {"events.*"};
        const auto results = run_protocol_checks(*b.session, *node, o, ctx);
        for (const char* id : {"events.pcer-payload-tolerated", "events.learn-tolerated"}) {
            const CheckResult& c = expect_status(results, id, Status::kPass);
            EXPECT_EQ(c.category, Category::kEvents) << file;
        }
    }
}

TEST(EventRobustnessTest, LearnEventIsSentOnlyWithThorough) {
    const auto results = testing::protocol_results();
    expect_status(results, "events.pcer-payload-tolerated", Status::kPass);
    EXPECT_EQ(testing::find_check(results, "events.learn-tolerated"), nullptr);
}

// events.identify-producer-consumer and events.pcer-payload-tolerated, run as a node run runs
// them: their results and the simulated time they took together.
std::vector<CheckResult> identify_then_pcers(SimBench& b, const NodeInfo& node, Duration& took) {
    std::vector<CheckSpec> specs;
    for (const CheckSpec& spec : checks::event_checks())
        if (spec.id == "events.identify-producer-consumer") specs.push_back(spec);
    for (const CheckSpec& spec : checks::event_robustness_checks())
        if (spec.id == "events.pcer-payload-tolerated") specs.push_back(spec);
    CheckRun run(*b.session, node, ProtocolOptions{});
    run.probe<EventAnswers>(IdentifyTo::kEveryNode);  // the reference the asks are taken from
    const TimePoint start = b.net.now();
    for (const CheckSpec& spec : specs) run.run(spec);
    took = b.net.now() - start;
    return run.take();
}

// Issue 32: the silence a foreign event is owed and the watch for a restart after the PCERs
// are one window, not two.
TEST(EventRobustnessTest, TheIdentifyAsksAndThePcersShareOneWindow) {
    SimBench b;
    auto node = b.start();
    ASSERT_TRUE(node);
    Duration took{};
    const auto results = identify_then_pcers(b, *node, took);
    expect_status(results, "events.identify-producer-consumer", Status::kPass);
    expect_status(results, "events.pcer-payload-tolerated", Status::kPass);
    const Duration window = ProtocolOptions{}.window;
    EXPECT_GE(took, window);
    EXPECT_LT(took, window + window / 2)
        << std::chrono::duration_cast<std::chrono::milliseconds>(took).count() << " ms";
}

// The PCERs go out only after the owed Identified answers came: a node they silence has
// answered the asks, so identify-producer-consumer judges the asks and only the PCER check fails.
TEST(EventRobustnessTest, ANodeThePcersSilenceHadAnsweredTheAsksFirst) {
    SimBench b;
    auto node = b.start();
    ASSERT_TRUE(node);
    auto deaf = std::make_shared<bool>(false);
    b.dut->stack().set_inbound_filter([deaf](const CanFrame& f, TimePoint) {
        if (f.extended && can::is_message(f.id) &&
            can::can_mti(f.id) == can::kCanMtiPcerPayloadFirst)
            *deaf = true;
        return FrameRoute{!*deaf, !*deaf};
    });
    Duration took{};
    const auto results = identify_then_pcers(b, *node, took);
    expect_status(results, "events.identify-producer-consumer", Status::kPass);
    const CheckResult& pcer =
        expect_status(results, "events.pcer-payload-tolerated", Status::kFail);
    EXPECT_TRUE(testing::contains(pcer.message, "no longer answers")) << pcer.message;
}

}  // namespace
}  // namespace olcb::conform
