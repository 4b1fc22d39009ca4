// The runner's link on a SimNetwork: its node is the tool's, every frame in or out is observed,
// and waiting advances simulated time by exactly the bound when nothing happens.
#include <gtest/gtest.h>

#include <chrono>
#include <cstddef>

#include "conformance/conform_test_util.hpp"
#include "conformance/link/link.hpp"
#include "openlcb/sim_network.hpp"

namespace olcb::conform {
namespace {

using namespace std::chrono_literals;

TEST(SimLinkTest, TheToolsNodeReservesItsAliasAndEveryFrameIsObserved) {
    SimNetwork net;
    net.set_logging(false);
    auto link = make_sim_link(net, kTool);
    std::size_t observed = 0;
    link->set_frame_observer([&](const CanFrame&, TimePoint) { ++observed; });
    EXPECT_EQ(link->stack().node_id(), kTool);
    EXPECT_TRUE(link->run_until([&] { return link->stack().initialized(); }, 2s));
    // The CIDs went out as the link was made; RID, AMD and Initialization Complete after.
    EXPECT_GE(observed, 3u);
}

TEST(SimLinkTest, AWaitForWhatNeverHappensTakesTheWholeBound) {
    SimNetwork net;
    net.set_logging(false);
    auto link = make_sim_link(net, kTool);
    link->run_until({}, 1s);  // the start-up, out of the way
    const TimePoint before = link->now();
    EXPECT_FALSE(link->run_until([] { return false; }, 700ms));
    EXPECT_EQ(link->now() - before, 700ms);
}

TEST(SimLinkTest, TheToolResendsTemporaryRejectsAndNeverWaitsLongForAnAck) {
    const NodeStackConfig c = tool_stack_config(kTool);
    EXPECT_EQ(c.node_id, kTool);
    EXPECT_GE(c.datagram_sender.max_resends, 3u);
    EXPECT_LE(c.datagram_sender.ack_timeout, 1s);
    EXPECT_FALSE(c.stream.accept_unsolicited);
}

}  // namespace
}  // namespace olcb::conform
