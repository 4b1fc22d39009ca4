// Two NodeStacks on one SimNetwork: they learn each other, exchange datagrams, and one restarts
// while the other stays connected (the network itself: sim_network_test.cpp).
#include <gtest/gtest.h>

#include <cstdint>
#include <string>
#include <vector>

#include "base/timings.hpp"
#include "openlcb/datagram_defs.hpp"
#include "openlcb/node_test_util.hpp"

namespace olcb {
namespace {

using namespace std::chrono_literals;
using namespace test;
using Status = DatagramOutcome::Status;

std::vector<std::uint8_t> read_reply_payload() {
    std::vector<std::uint8_t> p = {0x20, 0x53, 0, 0, 0, 0};
    for (int i = 0; i < 64; ++i) p.push_back(static_cast<std::uint8_t>('a' + i % 26));
    return p;
}

// The worked example's node (alias 343) and runner (alias 12C) on one network.
class PairTest : public test::PairFixture {};

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

}  // namespace
}  // namespace olcb
