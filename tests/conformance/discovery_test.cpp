// Finding nodes and timing on the simulated clock: a node that starts after the tool is found
// from its Initialization Complete, discovery ends once no new node appears, another tool's CID
// probe is not taken for a restart, and the run's windows follow the measured latency.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>
#include <pugixml.hpp>

#include "conformance/report/report.hpp"
#include "conformance/report/run_timing.hpp"
#include "conformance/sim_bench.hpp"
#include "openlcb/can_defs.hpp"
#include "support/report_schema.hpp"

namespace olcb::conform {
namespace {

using std::chrono::milliseconds;
using testing::default_cdi;
using testing::SimBench;

// A simnode that starts `delay` after the tool's session (a node just powered on).
struct LateNode {
    SimNetwork net;
    std::unique_ptr<simnode::SimNode> dut;
    std::unique_ptr<Link> link;
    std::unique_ptr<Session> session;

    explicit LateNode(Duration delay) {
        std::string error;
        simnode::NodeConfig cfg;
        cfg.node_id = kDut;
        cfg.cdi = default_cdi();
        dut = simnode::SimNode::create(cfg, error);
        EXPECT_TRUE(dut) << error;
        net.set_logging(false);
        net.add_stack(dut->stack());
        dut->stack().schedule(net.now() + delay, [this](TimePoint t) { dut->stack().start(t); });
        link = make_sim_link(net, kTool);
        session = std::make_unique<Session>(*link);
        EXPECT_TRUE(session->start());
    }
};

TEST(Discovery, ANodeStillReservingItsAliasIsFoundByNodeId) {
    LateNode late(milliseconds(300));
    const TimePoint asked = late.net.now();
    auto node = late.session->find_node(kDut, std::chrono::seconds(3));
    ASSERT_TRUE(node);
    EXPECT_EQ(node->alias, late.dut->stack().alias());
    EXPECT_LT(late.net.now() - asked, std::chrono::seconds(1));
}

TEST(Discovery, ANodeStartingDuringDiscoveryIsFound) {
    LateNode late(milliseconds(700));
    auto nodes = late.session->discover(std::chrono::seconds(3));
    ASSERT_EQ(nodes.size(), 1u);
    EXPECT_EQ(nodes[0].id, kDut);
}

TEST(Discovery, EndsOnceNoNewNodeAppearedForTheQuietPeriod) {
    SimBench b;
    ASSERT_TRUE(b.session->start());
    const TimePoint asked = b.net.now();
    auto nodes = b.session->discover(std::chrono::seconds(3), milliseconds(500));
    ASSERT_EQ(nodes.size(), 1u);
    EXPECT_LT(b.net.now() - asked, std::chrono::seconds(1));  // not the whole 3 s
}

TEST(Discovery, NothingOnTheSegmentTakesTheWholeBoundAndFindsNothing) {
    SimNetwork net;
    auto link = make_sim_link(net, kTool);
    Session session(*link);
    ASSERT_TRUE(session.start());
    const TimePoint asked = net.now();
    EXPECT_TRUE(session.discover(std::chrono::seconds(2)).empty());
    EXPECT_GE(net.now() - asked, std::chrono::seconds(2));
}

TEST(NodeTrackTest, AnotherToolsCidProbeAndAmeAreNoRestart) {
    SimBench b;
    auto node = b.start();
    ASSERT_TRUE(node);
    const NodeTrack before = b.session->track(kDut);
    // Sent on the segment as another tool would: not through our session's inject().
    b.link->send_frame(can::make_cid(7, NodeId{0x020112FE0001ull}, node->alias));
    b.link->send_frame(can::make_ame(0x123));
    b.session->wait(milliseconds(300));
    EXPECT_EQ(b.session->track(kDut).reservations, before.reservations);
    ASSERT_TRUE(b.reboot(*node));
    EXPECT_EQ(b.session->track(kDut).reservations, before.reservations + 1);
}

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

TEST(RunReports, TimingIsInTheJsonAndARunErrorInBothReports) {
    NodeReport r;
    r.node_id = "05.01.01.01.22.00";
    r.timing = derive_timing({milliseconds(40)}, 1.0);
    RunInfo run;
    run.late_nodes = {"05.01.01.01.22.10"};
    auto j = nlohmann::json::parse(to_json({r}, run));
    EXPECT_EQ(test::json_report_errors(to_json({r}, run)), "");
    EXPECT_EQ(j["nodes"][0]["timing"]["latency_ms"], 40);
    EXPECT_EQ(j["nodes"][0]["timing"]["silence_ms"], 250);
    EXPECT_EQ(j["run"]["late_nodes"][0], "05.01.01.01.22.10");
    run.error = "no node answered Verify Node ID";
    j = nlohmann::json::parse(to_json({}, run));
    EXPECT_EQ(test::json_report_errors(to_json({}, run)), "");
    EXPECT_EQ(j["run"]["error"], run.error);
    EXPECT_TRUE(j["nodes"].empty());
    pugi::xml_document doc;
    EXPECT_EQ(test::junit_report_errors(to_junit({}, run)), "");
    ASSERT_TRUE(doc.load_string(to_junit({}, run).c_str()));
    auto error = doc.select_node("//testsuite[@name='lcc-conform']/testcase/error");
    ASSERT_TRUE(error);
    EXPECT_EQ(std::string(error.node().attribute("message").value()), run.error);
}

}  // namespace
}  // namespace olcb::conform
