// The event checks (conformance/checks/events.cpp) against the simulated node: every one passes
// on the default and io-board nodes, each catches its fault, events.follow-write puts the
// original back, and the whole set of new checks stays under a second of simulated time.
#include <gtest/gtest.h>

#include <map>

#include "conformance/checks/check_run.hpp"
#include "conformance/checks/checks.hpp"
#include "conformance/checks/events.hpp"
#include "conformance/checks/probes.hpp"
#include "conformance/sim_bench.hpp"
#include "openlcb/can_defs.hpp"

namespace olcb::conform {
namespace {

using testing::contains;
using testing::dump;
using testing::expect_status;
using testing::find_check;
using testing::io_board_cdi;
using testing::SimBench;

std::vector<CheckResult> run_specs(SimBench& b, const std::vector<CheckSpec>& specs,
                                   CheckContext& ctx) {
    auto node = b.start();
    if (!node) return {};
    CheckRun run(*b.session, *node, ProtocolOptions{});
    for (const CheckSpec& spec : specs) run.run(spec);
    hand_over(run, ctx);
    return run.take();
}

std::vector<CheckResult> run_events(SimBench& b) {
    CheckContext ctx;
    return run_specs(b, checks::event_checks(), ctx);
}

// The follow-write check after the read-only checks handed over what they learned (the layout).
std::vector<CheckResult> follow_write(SimBench& b, const ProtectionRules& rules = {}) {
    CheckContext ctx;
    run_specs(b, checks::event_checks(), ctx);
    return checks::events_follow_write(*b.session, *b.session->find_node(kDut), ctx, rules);
}

std::vector<std::uint8_t> config_bytes(SimBench& b) {
    return b.dut->memory().read(0xFD, 0, 1u << 16);
}

TEST(EventChecksTest, DefaultNodePasses) {
    SimBench b;
    const auto results = run_events(b);
    ASSERT_EQ(results.size(), 4u) << dump(results);
    for (const auto& r : results) {
        EXPECT_EQ(r.status, Status::kPass) << dump(results);
        EXPECT_EQ(r.category, Category::kEvents) << r.id;
    }
    const auto& g = expect_status(results, "events.identify-global", Status::kPass);
    EXPECT_TRUE(contains(g.message, "8 consumed")) << g.message;
    const auto& pc = expect_status(results, "events.identify-producer-consumer", Status::kPass);
    EXPECT_TRUE(contains(pc.message, "no produced event identified")) << pc.message;
    EXPECT_TRUE(contains(pc.message, "05.01.01.01.3F.FF.FF.FE")) << pc.message;
    expect_status(results, "events.cdi-events-identified", Status::kPass);
}

TEST(EventChecksTest, IoBoardNodePassesWithBothRoles) {
    SimBench b({}, io_board_cdi());
    const auto results = run_events(b);
    for (const auto& r : results) EXPECT_EQ(r.status, Status::kPass) << dump(results);
    const auto& pc = expect_status(results, "events.identify-producer-consumer", Status::kPass);
    EXPECT_TRUE(contains(pc.message, "Producer Identified")) << pc.message;
    EXPECT_TRUE(contains(pc.message, "Consumer Identified")) << pc.message;
    const auto& cdi = expect_status(results, "events.cdi-events-identified", Status::kPass);
    EXPECT_TRUE(contains(cdi.message, "all 64 event IDs")) << cdi.message;
}

TEST(EventChecksTest, MissingEventsWarnListingThem) {
    SimBench b({"events-missing"}, io_board_cdi());
    const auto results = run_events(b);
    const auto& c = expect_status(results, "events.cdi-events-identified", Status::kWarn);
    EXPECT_TRUE(contains(c.message, "32 of 64 event IDs")) << c.message;
    EXPECT_EQ(c.details.size(), 32u);
    EXPECT_TRUE(contains(c.details.front(), "Lines(0).")) << c.details.front();
    // What it identifies it identifies the same way every time.
    expect_status(results, "events.identify-global", Status::kPass);
    expect_status(results, "events.identify-addressed", Status::kPass);
    expect_status(results, "events.identify-producer-consumer", Status::kPass);
}

TEST(EventChecksTest, EachCheckWorksOnItsOwn) {
    for (const CheckSpec& spec : checks::event_checks()) {
        SimBench b;
        CheckContext ctx;
        const auto results = run_specs(b, {spec}, ctx);
        ASSERT_EQ(results.size(), 1u) << spec.id << "\n" << dump(results);
        EXPECT_EQ(results[0].status, Status::kPass) << dump(results);
    }
}

// The two Identify Events checks: their results and the simulated time they took.
std::vector<CheckResult> identify_both(SimBench& b, const NodeInfo& node, Duration& took) {
    CheckRun run(*b.session, node, ProtocolOptions{});
    const TimePoint start = b.net.now();
    for (const CheckSpec& spec : checks::event_checks())
        if (spec.id == "events.identify-global" || spec.id == "events.identify-addressed")
            run.run(spec);
    took = b.net.now() - start;
    return run.take();
}

std::vector<CheckResult> identify_both(SimBench& b, Duration& took) {
    auto node = b.start();
    if (!node) return {};
    return identify_both(b, *node, took);
}

// OpenMRN's time_server, sent Identify Events addressed while it answered the global one, left
// out its Producer Identified messages and answered no Query until restarted: the addressed form
// goes out only once the global one's answers have ended.
TEST(EventChecksTest, TheTwoIdentifyFormsAreNeverInFlightTogether) {
    SimBench b;
    auto node = b.start();
    ASSERT_TRUE(node);
    auto sent = std::make_shared<std::map<int, TimePoint>>();  // CAN-MTI -> when the tool sent it
    const std::uint16_t alias = node->alias;
    b.net.add_endpoint([sent, alias](const CanFrame& f, TimePoint at) {
        if (!f.extended || !can::is_message(f.id) || can::source_alias(f.id) == alias) return;
        const int mti = can::can_mti(f.id);
        if (mti == 0x970 || mti == 0x968) sent->emplace(mti, at);
    });
    Duration took{};
    const auto results = identify_both(b, *node, took);
    expect_status(results, "events.identify-global", Status::kPass);
    expect_status(results, "events.identify-addressed", Status::kPass);
    ASSERT_EQ(sent->size(), 2u);
    const Duration gap = sent->at(0x968) - sent->at(0x970);
    EXPECT_GE(gap, std::chrono::milliseconds(200))  // the global form's quiet window
        << std::chrono::duration_cast<std::chrono::milliseconds>(gap).count() << " ms";
}

TEST(EventChecksTest, AnAddressedIdentifyIgnoredIsToldFromTheGlobalOne) {
    SimBench b;
    // The node never sees Identify Events addressed (CAN-MTI 0x968): only global is answered.
    NodeStack& dut = b.dut->stack();
    dut.set_inbound_filter([](const CanFrame& f, TimePoint) {
        const bool addressed_identify = can::is_message(f.id) && can::can_mti(f.id) == 0x968;
        return FrameRoute{true, !addressed_identify};
    });
    Duration took{};
    const auto results = identify_both(b, took);
    expect_status(results, "events.identify-global", Status::kPass);
    EXPECT_NE(find_check(results, "events.identify-addressed")->status, Status::kPass)
        << dump(results);
}

// OpenMRN's io_board names some events twice in each answer: both forms still pass.
TEST(EventChecksTest, EventsNamedTwicePerAnswerPass) {
    SimBench b;
    auto node = b.start();
    ASSERT_TRUE(node);
    // In the node's name, one more Consumer Identified of its first event per Identify Events.
    const std::uint16_t alias = node->alias;
    auto port = std::make_shared<Transport*>(nullptr);
    *port = &b.net.add_endpoint([port, alias](const CanFrame& f, TimePoint) {
        const bool identify = f.extended && can::is_message(f.id) &&
                              can::source_alias(f.id) != alias &&
                              (can::can_mti(f.id) == 0x970 || can::can_mti(f.id) == 0x968);
        if (!identify) return;
        (*port)->send(can::make_frame(can::message_header(0x4C7, alias),
                                      std::array<std::uint8_t, 8>{5, 1, 1, 1, 0x22, 0, 0, 0}));
    });
    Duration took{};
    const auto results = identify_both(b, *node, took);
    const auto& g = expect_status(results, "events.identify-global", Status::kPass);
    EXPECT_TRUE(contains(g.message, "9 Identified messages")) << g.message;
    expect_status(results, "events.identify-addressed", Status::kPass);
}

TEST(EventChecksTest, NewChecksTakeUnderASecondOnTheDefaultNode) {
    SimBench b;
    auto node = b.start();
    ASSERT_TRUE(node);
    std::vector<CheckSpec> specs = checks::memory_bounds_checks();
    const std::vector<CheckSpec> events = checks::event_checks();
    specs.insert(specs.end(), events.begin(), events.end());
    CheckRun run(*b.session, *node, ProtocolOptions{});
    const TimePoint start = b.net.now();
    for (const CheckSpec& spec : specs) run.run(spec);
    const Duration took = b.net.now() - start;
    const auto results = run.take();
    for (const auto& r : results) EXPECT_NE(r.status, Status::kFail) << dump(results);
    EXPECT_LT(took, std::chrono::seconds(1))
        << std::chrono::duration_cast<std::chrono::milliseconds>(took).count() << " ms";
}

TEST(EventFollowWriteTest, DefaultNodeFollowsAndTheOriginalIsBack) {
    SimBench b;
    const auto before = config_bytes(b);
    const auto results = follow_write(b);
    ASSERT_EQ(results.size(), 1u) << dump(results);
    EXPECT_EQ(results[0].id, "events.follow-write");
    EXPECT_EQ(results[0].category, Category::kEvents);
    EXPECT_EQ(results[0].status, Status::kPass) << dump(results);
    EXPECT_TRUE(contains(results[0].message, "05.01.01.01.3F.FE.")) << results[0].message;
    EXPECT_EQ(config_bytes(b), before);
}

TEST(EventFollowWriteTest, IoBoardNodeFollows) {
    SimBench b({}, io_board_cdi());
    const auto before = config_bytes(b);
    const auto results = follow_write(b);
    ASSERT_EQ(results.size(), 1u) << dump(results);
    EXPECT_EQ(results[0].status, Status::kPass) << dump(results);
    EXPECT_EQ(config_bytes(b), before);
}

TEST(EventFollowWriteTest, StaleEventsFailAndTheOriginalIsBack) {
    SimBench b({"events-stale-after-write"});
    const auto before = config_bytes(b);
    const auto results = follow_write(b);
    ASSERT_EQ(results.size(), 1u) << dump(results);
    EXPECT_EQ(results[0].status, Status::kFail) << dump(results);
    EXPECT_TRUE(contains(results[0].message, "no answer")) << results[0].message;
    EXPECT_TRUE(contains(results[0].message, "still identified")) << results[0].message;
    EXPECT_EQ(config_bytes(b), before);
}

TEST(EventFollowWriteTest, ExcludedVariablesAreNeverWritten) {
    SimBench b;
    const auto before = config_bytes(b);
    ProtectionRules rules;
    rules.exclude = {"*event*"};
    const auto results = follow_write(b, rules);
    ASSERT_EQ(results.size(), 1u) << dump(results);
    EXPECT_EQ(results[0].status, Status::kSkip) << dump(results);
    EXPECT_TRUE(contains(results[0].message, "nothing written")) << results[0].message;
    EXPECT_EQ(config_bytes(b), before);
}

}  // namespace
}  // namespace olcb::conform
