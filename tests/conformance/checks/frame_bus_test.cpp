// The frame_bus_checks() entries against the simulated node: every one passes on the default
// node (quickly), and each fails on a node with the fault it is about.
#include <gtest/gtest.h>

#include <chrono>
#include <string>
#include <variant>
#include <vector>

#include "conformance/checks/check_run.hpp"
#include "conformance/checks/checks.hpp"
#include "conformance/run/node_watch.hpp"
#include "conformance/sim_bench.hpp"
#include "openlcb/can_defs.hpp"

namespace olcb::conform {
namespace {

using namespace std::chrono_literals;
using testing::dump;
using testing::find_check;
using testing::SimBench;

// Runs the entries of list (only the one with ID `only`, when given) against node.
std::vector<CheckResult> run_list(Session& s, const NodeInfo& node,
                                  const std::vector<CheckSpec>& list, const ProtocolOptions& o = {},
                                  std::string_view only = {}) {
    CheckRun run(s, node, o);
    for (const CheckSpec& spec : list)
        if (only.empty() || spec.id == only) run.run(spec);
    return run.take();
}

// The one result of entry id from a node with these simnode faults.
CheckResult one(const std::vector<std::string>& faults, std::string_view id,
                const ProtocolOptions& o = {}) {
    SimBench b(faults);
    auto node = b.start();
    if (!node) return {};
    auto results = run_list(*b.session, *node, checks::frame_bus_checks(), o, id);
    EXPECT_EQ(results.size(), 1u) << dump(results);
    return results.empty() ? CheckResult{} : results.front();
}

TEST(FrameBusChecksTest, DefaultNodePassesQuickly) {
    SimBench b;
    auto node = b.start();
    ASSERT_TRUE(node);
    NodeWatch watch(*b.session, *node);
    const TimePoint t0 = b.net.now();
    auto results = run_list(*b.session, *node, checks::frame_bus_checks());
    const Duration took = b.net.now() - t0;
    ASSERT_EQ(results.size(), checks::frame_bus_checks().size()) << dump(results);
    for (const auto& r : results) {
        if (r.id == "frame.startup-sequence") {
            EXPECT_EQ(r.status, Status::kSkip) << r.message;  // needs --reboot
            continue;
        }
        EXPECT_EQ(r.status, Status::kPass) << dump(results);
        EXPECT_EQ(r.category, Category::kFrame) << r.id;
    }
    EXPECT_LT(took, 600ms) << std::chrono::duration_cast<std::chrono::milliseconds>(took).count();
    // The collision moved the node to a new alias; the session followed it.
    EXPECT_NE(b.session->alias_of(*node), node->alias);
    EXPECT_EQ(b.session->alias_of(*node), b.dut->stack().alias());
    EXPECT_TRUE(b.session->ping(*node, 1s));
    // The staged collision's new alias is no restart for the node watch.
    EXPECT_FALSE(watch.check_now("running the frame checks"));
}

TEST(FrameBusChecksTest, CollisionFailsWhenTheAliasIsNotGivenUp) {
    const CheckResult r = one({"alias-conflict-ignored"}, "frame.collision");
    EXPECT_EQ(r.status, Status::kFail);
    EXPECT_NE(r.message.find("no AMR"), std::string::npos) << r.message;
}

TEST(FrameBusChecksTest, AmeBit28FailsOnANodeThatStopped) {
    SimBench b;
    auto node = b.start();
    ASSERT_TRUE(node);
    b.dut->stack().go_silent(b.net.now());
    auto r = run_list(*b.session, *node, checks::frame_bus_checks(), {}, "frame.ame-bit28");
    ASSERT_EQ(r.size(), 1u);
    EXPECT_EQ(r[0].status, Status::kFail) << r[0].message;
}

// No clause sets a throughput a node must take: a dropped Verify after a burst is a WARN.
TEST(FrameBusChecksTest, CapacityWarnsWhenBurstsDropAddressedMessages) {
    const CheckResult r = one({"burst-drops"}, "frame.capacity");
    EXPECT_EQ(r.status, Status::kWarn);
    for (const char* variant :
         {"global Verify Node ID", "2-frame messages to another node", "Identify Consumer"})
        EXPECT_NE(r.message.find(variant), std::string::npos) << r.message;
}

TEST(FrameBusChecksTest, StandardFramesFailWhenAnswered) {
    const CheckResult r = one({"answers-standard-frames"}, "frame.standard-frames-ignored");
    EXPECT_EQ(r.status, Status::kFail);
    EXPECT_NE(r.seen.find("Verified Node ID"), std::string::npos) << r.seen;
}

// The addressing probes' silence window and fr60's, in one CheckRun: from the shared window
// when the node stays silent in it; each from a window of its own once the node speaks.
std::vector<CheckResult> addressing_then_standard(const std::vector<std::string>& faults,
                                                  Duration& standard_took) {
    SimBench b(faults);
    auto node = b.start();
    if (!node) return {};
    CheckRun run(*b.session, *node, {});
    for (const CheckSpec& spec : checks::message_addressing_checks()) run.run(spec);
    const TimePoint t0 = b.net.now();
    for (const CheckSpec& spec : checks::frame_bus_checks())
        if (spec.id == "frame.standard-frames-ignored") run.run(spec);
    standard_took = b.net.now() - t0;
    return run.take();
}

TEST(FrameBusChecksTest, StandardFramesShareTheAddressingProbesWindow) {
    Duration took{};
    const auto results = addressing_then_standard({}, took);
    const CheckResult* r = find_check(results, "frame.standard-frames-ignored");
    ASSERT_NE(r, nullptr) << dump(results);
    EXPECT_EQ(r->status, Status::kPass) << r->message;
    EXPECT_NE(r->message.find("shared"), std::string::npos) << r->message;
    EXPECT_EQ(took, Duration::zero());

    const auto bad = addressing_then_standard({"answers-standard-frames"}, took);
    // The answers to the standard frames neither pass fr60 nor count against the probes.
    EXPECT_EQ(find_check(bad, "frame.standard-frames-ignored")->status, Status::kFail);
    EXPECT_GT(took, Duration::zero());
    for (const char* id :
         {"message.verify-other-silent", "message.pip-other-silent", "message.oir-other-silent"})
        EXPECT_EQ(find_check(bad, id)->status, Status::kPass) << dump(bad);
}

TEST(FrameBusChecksTest, StandardFramesThoroughSendsAll2047) {
    ProtocolOptions o;
    o.selection.thorough = true;
    const CheckResult r = one({}, "frame.standard-frames-ignored", o);
    EXPECT_EQ(r.status, Status::kPass) << r.message;
    EXPECT_NE(r.message.find("2047 standard"), std::string::npos) << r.message;
    const CheckResult bad = one({"answers-standard-frames"}, "frame.standard-frames-ignored", o);
    EXPECT_EQ(bad.status, Status::kFail);
}

TEST(FrameBusChecksTest, StartupSequencePassesAfterReboot) {
    ProtocolOptions o;
    o.reboot = true;
    for (const char* fault : {"", "new-alias-on-reboot"}) {
        SimBench b(*fault ? std::vector<std::string>{fault} : std::vector<std::string>{});
        auto node = b.start();
        ASSERT_TRUE(node);
        NodeWatch watch(*b.session, *node);
        auto r =
            run_list(*b.session, *node, checks::frame_bus_checks(), o, "frame.startup-sequence");
        ASSERT_EQ(r.size(), 1u);
        EXPECT_EQ(r[0].status, Status::kPass) << fault << ": " << r[0].message;
        // The Reset was the check's: no restart for the node watch, and the node answers.
        EXPECT_FALSE(watch.check_now("after the start-up check")) << fault;
        EXPECT_EQ(b.session->alias_of(*node), b.dut->stack().alias()) << fault;
    }
}

TEST(FrameBusChecksTest, StartupSequenceSkipsQuotingTheRejectCode) {
    ProtocolOptions o;
    o.reboot = true;
    const CheckResult r = one({"reset-rejected"}, "frame.startup-sequence", o);
    EXPECT_EQ(r.status, Status::kSkip);
    EXPECT_NE(r.message.find("0x1041"), std::string::npos) << r.message;
}

TEST(FrameBusChecksTest, StartupSequenceFailsOnANodeThatNeverComesBack) {
    SimBench b;
    auto node = b.start();
    ASSERT_TRUE(node);
    b.dut->stack().go_silent(b.net.now());
    ProtocolOptions o;
    o.reboot = true;
    auto r = run_list(*b.session, *node, checks::frame_bus_checks(), o, "frame.startup-sequence");
    ASSERT_EQ(r.size(), 1u);
    EXPECT_EQ(r[0].status, Status::kFail);
    EXPECT_NE(r[0].message.find("no CID7"), std::string::npos) << r[0].message;
}

// A node that acknowledges Reset/Reboot, then goes through start-up without CID5.
TEST(FrameBusChecksTest, StartupSequenceFailsNamingTheFrameOutOfOrder) {
    SimNetwork net;
    net.set_logging(false);
    Transport& port = net.add_endpoint();
    testing::ScriptedNode fake(net, kDut);
    fake.answer = [&](const memory::Message& m) {
        if (!std::holds_alternative<memory::ResetReboot>(m)) return testing::ScriptedNode::Answer{};
        fake.stack.schedule(fake.stack.now() + 10ms, [&](TimePoint at) {
            fake.stack.go_silent(at);
            constexpr std::uint16_t kNew = 0x777;
            for (int n : {7, 6, 4}) port.send(can::make_cid(n, kDut, kNew));
            port.send(can::make_rid(kNew));
            port.send(can::make_amd(kNew, kDut));
            port.send(can::make_node_id_frame(
                can::message_header(to_u16(Mti::kInitializationComplete) & 0xFFF, kNew), kDut));
        });
        return testing::ScriptedNode::Answer{};
    };
    auto link = make_sim_link(net, kTool);
    Session s(*link);
    ASSERT_TRUE(s.start());
    auto node = s.find_node(kDut);
    ASSERT_TRUE(node);
    ProtocolOptions o;
    o.reboot = true;
    auto r = run_list(s, *node, checks::frame_bus_checks(), o, "frame.startup-sequence");
    ASSERT_EQ(r.size(), 1u);
    EXPECT_EQ(r[0].status, Status::kFail);
    EXPECT_NE(r[0].message.find("after CID6 from alias 0x777 came CID4"), std::string::npos)
        << r[0].message;
}

}  // namespace
}  // namespace olcb::conform
