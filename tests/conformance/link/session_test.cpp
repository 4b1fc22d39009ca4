// The Session finds nodes (one that starts after the tool from its Initialization Complete;
// discovery ends once no new node appears), follows each by node ID (a node that restarts on a new
// alias is reached there, another tool's CID probe is no restart) and never takes a short Read
// Reply for the end of a space.
#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "conformance/link/session.hpp"
#include "conformance/link/session_memory.hpp"
#include "conformance/link_test_util.hpp"
#include "conformance/sim_bench.hpp"
#include "openlcb/can_defs.hpp"

namespace olcb::conform {
namespace {

using namespace std::chrono_literals;
using memory::Space;
using std::chrono::milliseconds;
using testing::default_cdi;
using testing::SimBench;

TEST(NodeTrackTest, StartUpIsOneReservationAndOneInitialization) {
    SimBench b;
    auto node = b.start();
    ASSERT_TRUE(node);
    const NodeTrack t = b.session->track(kDut);
    EXPECT_EQ(t.alias, b.dut->stack().alias());
    EXPECT_EQ(t.reservations, 1u);
    EXPECT_EQ(t.initializations, 1u);
    EXPECT_LE(b.link->now() - t.last_heard, 10ms);  // its Verified Node ID just came
    EXPECT_EQ(b.session->track(NodeId{0x0501010122AAull}).alias, 0);
}

TEST(NodeTrackTest, ANodeThatRestartsOnANewAliasIsReachedThere) {
    SimBench b({"new-alias-on-reboot"});
    auto node = b.start();
    ASSERT_TRUE(node);
    const NodeTrack before = b.session->track(kDut);
    ASSERT_TRUE(b.reboot(*node));
    const NodeTrack after = b.session->track(kDut);
    ASSERT_NE(after.alias, node->alias) << "the fault should give a new alias";
    EXPECT_EQ(after.alias, b.dut->stack().alias());
    EXPECT_EQ(b.session->alias_of(*node), after.alias);
    EXPECT_EQ(after.reservations, before.reservations + 1);
    EXPECT_EQ(after.initializations, before.initializations + 1);
    // The NodeInfo still holds the old alias: every operation must use the tracked one.
    MemResult r = b.session->read(*node, Space::kCdi, 0, 5);
    ASSERT_TRUE(r.ok) << r.error;
    EXPECT_EQ(std::string(r.data.begin(), r.data.end()), "<?xml");
    EXPECT_TRUE(b.session->protocol_support(*node).has_value());
    EXPECT_TRUE(b.session->snip_payload(*node).has_value());
    EXPECT_TRUE(b.session->ping(*node, 500ms));
}

// A Reset the node performs without acknowledging (OpenLcbCLib) ends when the node is back,
// not after the acknowledgement and reply timeouts (simulated time: ~4 s before).
void expect_quick_unacknowledged_reset(const std::vector<std::string>& faults) {
    SimBench b(faults);
    auto node = b.start();
    ASSERT_TRUE(node);
    const std::uint32_t inits = b.session->track(kDut).initializations;
    static constexpr std::uint8_t kReset[] = {0x20, 0xA9};
    const TimePoint sent = b.link->now();
    const MemResult r = b.session->command(*node, kReset);
    const Duration spent = b.link->now() - sent;
    EXPECT_TRUE(r.restarted);
    EXPECT_FALSE(r.ok || r.rejected || r.timed_out);
    EXPECT_LT(spent, 1500ms) << std::chrono::duration_cast<milliseconds>(spent).count() << " ms";
    ASSERT_TRUE(
        b.link->run_until([&] { return b.session->track(kDut).initializations == inits + 1; }, 2s));
    // The next request is answered by the node's new run, on whichever alias it took.
    const MemResult read = b.session->read(*node, Space::kCdi, 0, 5);
    ASSERT_TRUE(read.ok) << read.error;
    EXPECT_EQ(std::string(read.data.begin(), read.data.end()), "<?xml");
}

// Another tool configuring the node shows as datagram frames to it from another alias: a run
// without the node's lock must not write then (NodeRun::take_lock).
TEST(SessionTest, DatagramSendersToANodeAreOtherAliasesOnly) {
    SimBench b;
    auto node = b.start();
    ASSERT_TRUE(node);
    const std::uint16_t dut = b.dut->stack().alias();
    EXPECT_TRUE(b.session->datagram_senders_to(dut).empty()) << "our own reads are not listed";
    ASSERT_TRUE(b.session->read_range(*node, Space::kConfig, 0, 8, false).ok);
    EXPECT_TRUE(b.session->datagram_senders_to(dut).empty());
    Transport& other = b.net.add_endpoint([](const CanFrame&, TimePoint) {});
    const std::array<std::uint8_t, 7> read = {0x20, 0x41, 0, 0, 0, 0, 8};
    other.send(
        can::make_frame(can::addressed_header(can::FrameFormat::kDatagramOnly, dut, 0x123), read));
    other.send(can::make_frame(can::addressed_header(can::FrameFormat::kDatagramOnly, 0x456, 0x124),
                               read));
    b.session->wait(10ms);
    const auto senders = b.session->datagram_senders_to(dut);
    ASSERT_EQ(senders.size(), 1u);
    EXPECT_EQ(senders[0].first, 0x123);
    EXPECT_FALSE(senders[0].second) << "no node ID announced for that alias";
}

TEST(SessionTest, AnUnacknowledgedResetEndsWhenTheNodeIsBackOnANewAlias) {
    expect_quick_unacknowledged_reset({"reset-unacknowledged", "new-alias-on-reboot"});
}

TEST(SessionTest, AnUnacknowledgedResetEndsWhenTheNodeIsBackOnItsAlias) {
    expect_quick_unacknowledged_reset({"reset-unacknowledged"});
}

TEST(SessionTest, AnAcknowledgedResetIsOk) {
    SimBench b;
    auto node = b.start();
    ASSERT_TRUE(node);
    static constexpr std::uint8_t kReset[] = {0x20, 0xA9};
    const MemResult r = b.session->command(*node, kReset);
    EXPECT_TRUE(r.ok);
    EXPECT_FALSE(r.restarted);
}

// A node that replies but never acknowledges (reply-without-ack) costs one acknowledgement
// timeout, when it is noted; then each reply ends its datagram's wait and the next read goes at
// once, its latency timed from when it left, not from when it was queued.
TEST(SessionTest, ANodeThatNeverAcknowledgesIsNotedOnceThenItsRepliesAreTaken) {
    SimBench b({"reply-without-ack"});
    auto node = b.start();
    ASSERT_TRUE(node);
    const Duration ack_timeout = b.link->stack().config().datagram_sender.ack_timeout;
    TimePoint start = b.link->now();
    for (int i = 0; i < 10; ++i) {
        const MemResult r = b.session->read(*node, Space::kCdi, 0, 5);
        ASSERT_TRUE(r.ok) << "read " << i << ": " << r.error;
        EXPECT_FALSE(r.datagram_ok_seen);
        EXPECT_LT(r.reply_latency, 100ms) << "read " << i << " timed from its queueing";
    }
    const Duration spent = b.link->now() - start;
    EXPECT_LT(spent, ack_timeout + 1s) << std::chrono::duration_cast<milliseconds>(spent).count();
    const NodeTrack t = b.session->track(kDut);
    EXPECT_TRUE(t.never_acks);
    EXPECT_EQ(t.unacknowledged, 10u);
    // A command with no reply cannot be confirmed: it ends after the answer window, marked.
    static constexpr std::uint8_t kUpdateComplete[] = {0x20, 0xA8};
    start = b.link->now();
    const MemResult r = b.session->command(*node, kUpdateComplete);
    EXPECT_TRUE(r.unacknowledged && r.timed_out);
    EXPECT_FALSE(r.ok);
    EXPECT_LE(b.link->now() - start, b.session->answer_timeout() + 50ms);
    EXPECT_TRUE(b.session->read(*node, Space::kCdi, 0, 5).ok) << "the next read goes at once";
}

TEST(SessionTest, AnOkAfterTheReplyIsNoNeverAcknowledgingNode) {
    SimBench b({"no-datagram-ack"});  // the reply first, then the OK
    auto node = b.start();
    ASSERT_TRUE(node);
    for (int i = 0; i < 3; ++i) {
        const MemResult r = b.session->read(*node, Space::kCdi, 0, 5);
        ASSERT_TRUE(r.ok) << r.error;
    }
    b.link->run_until([] { return false; }, 100ms);  // the last OK comes in
    const NodeTrack t = b.session->track(kDut);
    EXPECT_FALSE(t.never_acks);
    EXPECT_EQ(t.unacknowledged, 0u);
}

TEST(NodeTrackTest, ARestartOnTheSameAliasIsStillAReservation) {
    SimBench b;
    auto node = b.start();
    ASSERT_TRUE(node);
    ASSERT_TRUE(b.reboot(*node));
    const NodeTrack t = b.session->track(kDut);
    EXPECT_EQ(t.alias, node->alias);
    EXPECT_EQ(t.reservations, 2u);
    EXPECT_EQ(t.initializations, 2u);
}

TEST(NodeTrackTest, AnAmdAnsweringAnAmeOrADefenceIsNoReservation) {
    SimBench b;
    auto node = b.start();
    ASSERT_TRUE(node);
    const TimePoint heard = b.session->track(kDut).last_heard;
    b.session->wait(100ms);
    // CID with the node's alias: it defends with RID; then AMEs: it answers AMD, twice.
    b.session->inject(can::make_cid(7, NodeId{0x020112FE0001ull}, node->alias));
    b.session->wait(50ms);
    const std::size_t mark = b.session->frame_mark();
    b.session->inject(can::make_ame(b.session->tool_alias()));
    b.session->inject(can::make_ame(b.session->tool_alias(), kDut));
    b.session->wait(100ms);
    std::size_t amd = 0;
    for (const CanFrame& f : b.session->frames_since(mark)) {
        if (can::is_control(f.id) && can::source_alias(f.id) == node->alias &&
            can::classify_control(f.id) == can::ControlFrame::kAmd)
            ++amd;
    }
    ASSERT_EQ(amd, 2u);
    const NodeTrack t = b.session->track(kDut);
    EXPECT_EQ(t.reservations, 1u);
    EXPECT_EQ(t.alias, node->alias);
    EXPECT_GT(t.last_heard, heard);
}

TEST(NodeTrackTest, PingAnswersForAPresentNodeOnly) {
    SimBench b;
    auto node = b.start();
    ASSERT_TRUE(node);
    EXPECT_TRUE(b.session->ping(*node, 500ms));
    const TimePoint before = b.link->now();
    EXPECT_FALSE(b.session->ping(NodeInfo{NodeId{0x0501010122AAull}, 0x123}, 500ms));
    EXPECT_EQ(b.link->now() - before, 500ms);
}

// A TCP link cannot see the bus behind its hub: it assumes 125 kbit/s and waits out the frames it
// sent at that speed. An answer to a ping sent after them shows they are through, and ends that.
TEST(SessionBacklogTest, AnAnsweredPingEndsTheAssumedBacklogOfABurst) {
    SimNetwork net;
    std::string error;
    simnode::NodeConfig cfg;
    cfg.node_id = kDut;
    cfg.cdi = default_cdi();
    auto dut = simnode::SimNode::create(cfg, error);
    ASSERT_TRUE(dut) << error;
    net.set_logging(false);
    net.add_stack(dut->stack());
    dut->stack().start(net.now());
    auto link = make_sim_link(net, kTool, kLccBitrate);
    Session session(*link);
    ASSERT_TRUE(session.start());
    auto node = session.find_node(kDut);
    ASSERT_TRUE(node);
    // 300 global Verify Node IDs for another node from a made-up alias: ~0.38 s at 125 kbit/s.
    const CanFrame other = can::make_node_id_frame(
        can::message_header(to_u16(Mti::kVerifyNodeIdGlobal) & 0x0FFF, 0x0AB),
        NodeId{0x0501010122AAull});
    for (int i = 0; i < 300; ++i) session.inject(other);
    EXPECT_GT(session.backlog(), 300ms);
    const TimePoint before = link->now();
    ASSERT_TRUE(session.ping(*node, 500ms));
    EXPECT_LT(link->now() - before, 50ms) << "the unpaced node answers at once";
    EXPECT_EQ(session.backlog(), Duration::zero());
}

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

TEST(ShortReadTest, ReadRangeGoesOnWhereAShortReplyEnded) {
    SimBench b({"field-reads-only"});
    auto node = b.start();
    ASSERT_TRUE(node);
    MemResult m = b.session->read_range(*node, Space::kAcdiManufacturer, 0, 125, false);
    ASSERT_TRUE(m.ok);
    EXPECT_EQ(m.data.size(), 125u);
    EXPECT_EQ(m.data, testing::reference_bytes(Space::kAcdiManufacturer, 0, 125));
    ASSERT_FALSE(b.session->short_reads().empty());
    const ShortRead& first = b.session->short_reads().front();
    EXPECT_EQ(first.node, kDut);
    EXPECT_EQ(first.space, 0xFC);
    EXPECT_EQ(first.address, 0u);
    EXPECT_EQ(first.asked, 64);
    EXPECT_EQ(first.got, 1u);  // the version byte alone
    EXPECT_TRUE(first.continued);
    EXPECT_FALSE(first.at_end);
    EXPECT_GE(b.session->reads(kDut, 0xFC), 2u);
    EXPECT_EQ(b.session->reads(kDut, 0xFB), 0u);
}

TEST(ShortReadTest, TheEndOfTheSpaceEndsAReadAndIsRecorded) {
    SimBench b;
    auto node = b.start();
    ASSERT_TRUE(node);
    // 0xFF is smaller than 1 MiB: the reads end at 0x1082, ok with the whole space.
    MemResult all = b.session->read_range(*node, Space::kCdi, 0, 1u << 20, false);
    ASSERT_TRUE(all.ok);
    const std::size_t size = all.data.size();
    ASSERT_GT(size, 100u);
    EXPECT_EQ(all.data.back(), 0);  // the NUL is the last byte of the space
    ASSERT_EQ(b.session->short_reads().size(), 1u);
    const ShortRead& s = b.session->short_reads()[0];
    EXPECT_EQ(s.address + s.got, size);
    EXPECT_FALSE(s.continued);
    EXPECT_TRUE(s.at_end);
    SessionMemory memory(*b.session, *node);
    const auto last = static_cast<std::uint32_t>(size - 4);
    AccessResult tail = memory.read(0xFF, last, 100);
    ASSERT_TRUE(tail.ok);
    EXPECT_EQ(tail.data.size(), 4u);
    AccessResult past = memory.read(0xFF, static_cast<std::uint32_t>(size), 8);
    EXPECT_FALSE(past.ok);
    EXPECT_EQ(past.error, 0x1082);
}

}  // namespace
}  // namespace olcb::conform
