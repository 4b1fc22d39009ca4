// Several NodeStacks on one SimNetwork: datagram exchange, restart of one node while another
// stays connected, 1,000 nodes allocating distinct aliases, determinism and bus timing.
#include <gtest/gtest.h>

#include <algorithm>
#include <deque>
#include <set>

#include "base/timings.hpp"
#include "openlcb/datagram_defs.hpp"
#include "openlcb/node/node_test_util.hpp"

namespace olcb {
namespace {

using namespace std::chrono_literals;
using test::gc;
using test::kNodeId;
using test::kRunnerId;
using Strings = std::vector<std::string>;
using Status = DatagramOutcome::Status;

std::vector<std::uint8_t> read_reply_payload() {
    std::vector<std::uint8_t> p = {0x20, 0x53, 0, 0, 0, 0};
    for (int i = 0; i < 64; ++i) p.push_back(static_cast<std::uint8_t>('a' + i % 26));
    return p;
}

// The worked example's node (alias 343) and runner (alias 12C) on one network.
class PairTest : public ::testing::Test {
protected:
    PairTest() : node_(test::stack_config(kNodeId)), runner_(test::stack_config(kRunnerId)) {
        net_.add_stack(node_);
        net_.add_stack(runner_);
        net_.start_all();
        EXPECT_TRUE(
            net_.run_until([&] { return node_.initialized() && runner_.initialized(); }, 1s));
        net_.run_for(0ms);
        net_.clear_log();
    }

    SimNetwork net_;
    NodeStack node_;
    NodeStack runner_;
};

TEST_F(PairTest, BothStartAndLearnEachOther) {
    EXPECT_EQ(node_.alias(), 0x343);
    EXPECT_EQ(runner_.alias(), 0x12C);
    EXPECT_EQ(node_.alias_cache().alias_of(kRunnerId), 0x12C);
    EXPECT_EQ(runner_.alias_cache().node_of(0x343), kNodeId);
}

TEST_F(PairTest, VerifyNodeIdBetweenStacks) {
    std::vector<Message> heard;
    runner_.set_message_handler([&](const Message& m) {
        heard.push_back(m);
        return true;
    });
    Message verify;
    verify.mti = Mti::kVerifyNodeIdGlobal;
    EXPECT_EQ(runner_.send_message(verify), SendStatus::kSent);
    net_.run_for(0ms);
    EXPECT_EQ(net_.log_text(), (Strings{":X1949012CN;", ":X19170343N050101012200;"}));
    ASSERT_EQ(heard.size(), 1u);
    EXPECT_EQ(heard[0].mti, Mti::kVerifiedNodeId);
    EXPECT_EQ(heard[0].source, (NodeHandle{kNodeId, 0x343}));
}

TEST_F(PairTest, DatagramExchangeWithReplyPendingReplyAndAck) {
    std::vector<DatagramOutcome> runner_outcomes, node_outcomes;
    std::vector<ReceivedDatagram> runner_got;
    runner_.set_outcome_handler([&](const DatagramOutcome& o) { runner_outcomes.push_back(o); });
    node_.set_outcome_handler([&](const DatagramOutcome& o) { node_outcomes.push_back(o); });
    node_.set_datagram_handler([&](const ReceivedDatagram& d) {
        EXPECT_EQ(d.payload, (std::vector<std::uint8_t>{0x20, 0x43, 0, 0, 0, 0, 0x40}));
        node_.accept_datagram(d.source_alias, datagram::ok_flags(true));
        const auto reply = read_reply_payload();
        EXPECT_TRUE(node_.send_datagram(d.source_alias, reply, net_.now()).has_value());
    });
    runner_.set_datagram_handler([&](const ReceivedDatagram& d) {
        runner_got.push_back(d);
        runner_.accept_datagram(d.source_alias);
    });
    const std::vector<std::uint8_t> request = {0x20, 0x43, 0, 0, 0, 0, 0x40};
    const auto id = runner_.send_datagram(0x343, request, net_.now());
    ASSERT_TRUE(id.has_value());
    ASSERT_TRUE(net_.run_until([&] { return !node_outcomes.empty(); }, 1s));
    ASSERT_EQ(runner_outcomes.size(), 1u);
    EXPECT_EQ(runner_outcomes[0].id, *id);
    EXPECT_EQ(runner_outcomes[0].status, Status::kAccepted);
    EXPECT_EQ(runner_outcomes[0].flags, 0x80);
    ASSERT_EQ(runner_got.size(), 1u);
    EXPECT_EQ(runner_got[0].payload, read_reply_payload());
    EXPECT_EQ(node_outcomes[0].status, Status::kAccepted);
    EXPECT_EQ(node_outcomes[0].flags, 0x00);
    const Strings log = net_.log_text();
    ASSERT_EQ(log.size(), 1u + 1 + 9 + 1);
    EXPECT_EQ(log[0], ":X1A34312CN20430000000040;");
    EXPECT_EQ(log[1], ":X19A28343N012C80;");
    EXPECT_EQ(log[2], ":X1B12C343N2053000000006162;");
    EXPECT_EQ(log[10], ":X1D12C343N6768696A6B6C;");
    EXPECT_EQ(log[11], ":X19A2812CN034300;");
}

TEST_F(PairTest, UnansweredDatagramTimesOutAfterThreeSeconds) {
    node_.set_datagram_handler([](const ReceivedDatagram&) {});  // never answers
    std::vector<DatagramOutcome> outcomes;
    runner_.set_outcome_handler([&](const DatagramOutcome& o) { outcomes.push_back(o); });
    const TimePoint sent = net_.now();
    const std::vector<std::uint8_t> payload = {0x20, 0x80};
    ASSERT_TRUE(runner_.send_datagram(0x343, payload, sent));
    ASSERT_TRUE(net_.run_until([&] { return !outcomes.empty(); }, 10s));
    EXPECT_EQ(outcomes[0].status, Status::kTimedOut);
    EXPECT_EQ(net_.now(), sent + base::kDatagramAckTimeout);
}

TEST_F(PairTest, RestartOfOneNodeWhileTheOtherStaysConnected) {
    std::vector<DatagramOutcome> node_outcomes;
    node_.set_outcome_handler([&](const DatagramOutcome& o) { node_outcomes.push_back(o); });
    runner_.set_datagram_handler([](const ReceivedDatagram&) {});  // holds it unanswered
    const std::vector<std::uint8_t> payload = {0x20, 0x80};
    ASSERT_TRUE(node_.send_datagram(0x12C, payload, net_.now()));
    net_.run_for(0ms);
    net_.clear_log();
    node_.restart(net_.now());
    ASSERT_EQ(node_outcomes.size(), 1u);
    EXPECT_EQ(node_outcomes[0].status, Status::kAborted) << "a reboot loses the datagram";
    EXPECT_TRUE(runner_.initialized());
    ASSERT_TRUE(net_.run_until([&] { return node_.initialized(); }, 1s));
    net_.run_for(0ms);
    EXPECT_EQ(net_.log_text(),
              (Strings{":X17050343N;", ":X16101343N;", ":X15012343N;", ":X14200343N;",
                       ":X10700343N;", ":X10701343N050101012200;", ":X19100343N050101012200;"}));
    EXPECT_TRUE(runner_.initialized());
    EXPECT_EQ(runner_.alias(), 0x12C);
    EXPECT_EQ(runner_.alias_cache().alias_of(kNodeId), 0x343);
    // The pair still talks.
    net_.clear_log();
    Message verify;
    verify.mti = Mti::kVerifyNodeIdAddressed;
    verify.destination = NodeHandle{kNodeId, 0};
    EXPECT_EQ(runner_.send_message(verify), SendStatus::kSent);
    net_.run_for(0ms);
    EXPECT_EQ(net_.log_text(), (Strings{":X1948812CN0343;", ":X19170343N050101012200;"}));
}

TEST(SimNetworkTest, BusTimingDelaysFramesLikeCan) {
    SimNetwork net;
    net.enable_timing(125000);
    NodeStack a(test::stack_config(kNodeId));
    net.add_stack(a);
    const TimePoint t0 = net.now();
    net.start_all();
    ASSERT_TRUE(net.run_until([&] { return a.initialized(); }, 1s));
    net.run_for(10ms);
    ASSERT_EQ(net.log().size(), 7u);
    // CID frames carry no data: 80 bit times each at 125 kbit/s = 640 us.
    EXPECT_EQ(net.log()[0].at, t0 + 640us);
    EXPECT_EQ(net.log()[3].at, t0 + 4 * 640us);
    EXPECT_EQ(net.log()[4].at, t0 + 200ms + 640us) << "RID queued at +200 ms";
    EXPECT_GT(net.bus().busy_time(), 0ns);
}

// Node IDs whose first TN aliases all collide: the low two 12-bit groups are equal, so they
// cancel in the XOR and every node starts with alias 0x050 ^ 0x101 = 0x151.
NodeId colliding_id(std::uint32_t i) {
    return NodeId(0x050101000000ull | i << 12 | i);
}

TEST(SimNetworkScale, ThousandStacksWithCollidingFirstAliasesAllGetDistinctAliases) {
    constexpr int kCount = 1000;
    SimNetwork net;
    net.set_logging(false);
    std::deque<NodeStack> stacks;
    for (int i = 1; i <= kCount; ++i) {
        stacks.emplace_back(test::stack_config(colliding_id(static_cast<std::uint32_t>(i))));
        net.add_stack(stacks.back());
    }
    net.start_all();
    const TimePoint t0 = net.now();
    const bool done = net.run_until(
        [&] {
            return std::all_of(stacks.begin(), stacks.end(),
                               [](const NodeStack& s) { return s.initialized(); });
        },
        30s);
    ASSERT_TRUE(done) << "not all initialized within 30 s of simulated time";
    std::set<std::uint16_t> aliases;
    for (const auto& s : stacks) aliases.insert(s.alias());
    EXPECT_EQ(aliases.size(), static_cast<std::size_t>(kCount)) << "duplicate aliases";
    EXPECT_EQ(aliases.count(0), 0u);
    EXPECT_LT(net.now() - t0, 5s);
    // Quiet afterwards: no node lost its alias later.
    net.run_for(2s);
    std::set<std::uint16_t> after;
    for (const auto& s : stacks) {
        EXPECT_TRUE(s.initialized());
        after.insert(s.alias());
    }
    EXPECT_EQ(after, aliases);
}

TEST(SimNetworkScale, SameInputsGiveTheSameLog) {
    auto run = [] {
        SimNetwork net;
        std::deque<NodeStack> stacks;
        for (std::uint32_t i = 1; i <= 20; ++i) {
            stacks.emplace_back(test::stack_config(colliding_id(i)));
            net.add_stack(stacks.back());
        }
        net.start_all();
        net.run_for(3s);
        return net.log_text();
    };
    const Strings first = run();
    EXPECT_GT(first.size(), 20u * 7);
    EXPECT_EQ(run(), first);
}

TEST(SimNetworkTest, StacksMayOutliveTheNetwork) {
    NodeStack stack(test::stack_config());
    {
        SimNetwork net;
        net.add_stack(stack);
        net.start_all();
        net.run_for(300ms);
        EXPECT_TRUE(stack.initialized());
    }
    stack.restart(TimePoint{});  // new output after the network is gone: nobody is notified
    EXPECT_TRUE(stack.has_output());
}

TEST(SimNetworkTest, RunForAdvancesTheClockExactly) {
    SimNetwork net(TimePoint{} + 5h);
    EXPECT_EQ(net.now(), TimePoint{} + 5h);
    net.run_for(1500ms);
    EXPECT_EQ(net.now(), TimePoint{} + 5h + 1500ms);
    EXPECT_FALSE(net.run_until([] { return false; }, 1s));
    EXPECT_EQ(net.now(), TimePoint{} + 5h + 2500ms);
}

TEST(SimNetworkTest, EndlessSameInstantPingPongIsBounded) {
    SimNetwork net;
    Transport* a = nullptr;
    Transport* b = nullptr;
    a = &net.add_endpoint([&](const CanFrame& f, TimePoint) { a->send(f); });
    b = &net.add_endpoint([&](const CanFrame& f, TimePoint) { b->send(f); });
    a->send(gc(":X19490123N;"));
    net.set_max_steps(1000);
    EXPECT_FALSE(net.run_until([] { return false; }, 1s));
    EXPECT_TRUE(net.step_limit_hit());
}

TEST(SimNetworkTest, EndpointsSeeFramesWithTheirTime) {
    SimNetwork net;
    std::vector<TimePoint> times;
    Transport& tx = net.add_endpoint();
    net.add_endpoint([&](const CanFrame&, TimePoint t) { times.push_back(t); });
    net.run_for(1s);
    tx.send(gc(":X19490123N;"));
    net.run_for(0ms);
    ASSERT_EQ(times.size(), 1u);
    EXPECT_EQ(times[0], net.now());
    EXPECT_EQ(net.log_text(), (Strings{":X19490123N;"}));
    EXPECT_EQ(net.log_text(1), Strings{});
}

}  // namespace
}  // namespace olcb
