// A destination that re-initializes (memconfig_utils exits before acking, its next run comes back
// on the same alias) must not hold up the next datagram to it for the old one's ack timeout.
#include <gtest/gtest.h>

#include <algorithm>
#include <vector>

#include "base/timings.hpp"
#include "openlcb/datagram_defs.hpp"
#include "openlcb/node_test_util.hpp"

namespace olcb {
namespace {

using namespace std::chrono_literals;
using namespace test;
using Status = DatagramOutcome::Status;
using Bytes = std::vector<std::uint8_t>;

// The worked example's node (0x343) sends to the runner (0x12C), which never acks.
class ReinitPairTest : public test::PairFixture {
protected:
    ReinitPairTest() {
        node_.set_outcome_handler([this](const DatagramOutcome& o) { outcomes_.push_back(o); });
        runner_.set_datagram_handler([this](const ReceivedDatagram& d) { got_.push_back(d); });
    }

    // Sends A (never acked), optionally lets the runner re-initialize, then sends B; returns how
    // long B took to go on the wire.
    Duration delay_of_second_datagram(bool reinitialize) {
        EXPECT_TRUE(node_.send_datagram(0x12C, kA, net_.now()));
        net_.run_for(100ms);
        EXPECT_EQ(got_.size(), 1u);
        if (reinitialize) runner_.reinitialize(net_.now());  // same alias, fresh receiver
        net_.run_for(0ms);
        net_.clear_log();
        const TimePoint sent = net_.now();
        EXPECT_TRUE(node_.send_datagram(0x12C, kB, sent));
        const auto b_sent = [&] {
            const auto log = net_.log_text();
            return std::find(log.begin(), log.end(), ":X1A12C343N2081;") != log.end();
        };
        if (!net_.run_until(b_sent, 10s)) return Duration::max();
        return net_.now() - sent;
    }
    const Bytes kA = {0x20, 0x80};
    const Bytes kB = {0x20, 0x81};
    std::vector<DatagramOutcome> outcomes_;
    std::vector<ReceivedDatagram> got_;
};

TEST_F(ReinitPairTest, InitializationCompleteDropsTheUnackedDatagram) {
    EXPECT_EQ(delay_of_second_datagram(true), Duration::zero());
    ASSERT_EQ(got_.size(), 2u) << "the fresh receiver took B";
    EXPECT_EQ(got_[1].payload, kB);
    ASSERT_GE(outcomes_.size(), 1u);
    EXPECT_EQ(outcomes_[0].status, Status::kAborted);
    EXPECT_EQ(outcomes_[0].dest_alias, 0x12C);
    EXPECT_EQ(outcomes_.size(), 1u) << "B is still waiting for its ack";
}

TEST_F(ReinitPairTest, WithoutReinitializationTheNextDatagramWaitsForTheTimeout) {
    EXPECT_EQ(delay_of_second_datagram(false), base::kDatagramAckTimeout - 100ms);
    ASSERT_EQ(outcomes_.size(), 1u);
    EXPECT_EQ(outcomes_[0].status, Status::kTimedOut);
}

// The same with a raw port as the destination, for AMD and AME.
class ReinitPortTest : public test::StackFixture {
protected:
    ReinitPortTest() {
        boot();
        stack_.set_outcome_handler([this](const DatagramOutcome& o) { outcomes_.push_back(o); });
        EXPECT_TRUE(stack_.send_datagram(0x12C, Bytes{0x20, 0x80}, net_.now()));
        net_.run_for(100ms);
        EXPECT_EQ(take(), (std::vector<std::string>{":X1A12C343N2080;"}));
    }
    // Sends a second datagram; true when it went out at once.
    bool second_goes_out_at_once() {
        EXPECT_TRUE(stack_.send_datagram(0x12C, Bytes{0x20, 0x81}, net_.now()));
        net_.run_for(0ms);
        const auto frames = take();
        return std::find(frames.begin(), frames.end(), ":X1A12C343N2081;") != frames.end();
    }

    std::vector<DatagramOutcome> outcomes_;
};

TEST_F(ReinitPortTest, AmdFromTheDestinationDropsTheUnackedDatagram) {
    inject(":X1070112CN02010D000001;");
    ASSERT_EQ(outcomes_.size(), 1u);
    EXPECT_EQ(outcomes_[0].status, Status::kAborted);
    EXPECT_TRUE(second_goes_out_at_once());
}

TEST_F(ReinitPortTest, SimpleInitializationCompleteCountsToo) {
    inject(":X1910112CN02010D000001;");
    ASSERT_EQ(outcomes_.size(), 1u);
    EXPECT_EQ(outcomes_[0].status, Status::kAborted);
    EXPECT_TRUE(second_goes_out_at_once());
}

TEST_F(ReinitPortTest, AmdAnsweringAnAmeIsNoReinitialization) {
    inject(":X1070212CN;");  // AME: every node answers with AMD
    inject(":X1070112CN02010D000001;");
    EXPECT_TRUE(outcomes_.empty());
    EXPECT_FALSE(second_goes_out_at_once());
}

TEST_F(ReinitPortTest, OtherNodesReinitializingChangeNothing) {
    inject(":X19100555N020100000099;");
    EXPECT_TRUE(outcomes_.empty());
    EXPECT_FALSE(second_goes_out_at_once());
}

}  // namespace
}  // namespace olcb
