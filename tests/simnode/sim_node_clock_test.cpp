// Broadcast Time clocks of simulated nodes (SimNode with NodeConfig::clocks) on one simulated
// segment: a display follows a generator of another node, a node runs several clocks, and a
// restart keeps the time but sends the start-up sequence again.
#include <gtest/gtest.h>

#include <memory>
#include <string>
#include <vector>

#include "openlcb/sim_network.hpp"
#include "simnode/sim_node.hpp"
#include "simnode/sim_node_test_util.hpp"

namespace olcb::simnode {
namespace {

using namespace std::chrono_literals;

ClockConfig spec(const std::string& text) {
    std::string error;
    auto c = parse_clock_config(text, fast_time(2025, 1, 1, 0, 0), error);
    EXPECT_TRUE(c) << error;
    return c.value_or(ClockConfig{});
}

std::unique_ptr<SimNode> node(NodeId id, const std::vector<std::string>& clocks) {
    NodeConfig cfg;
    cfg.node_id = id;
    cfg.cdi = test::default_cdi();
    for (const auto& c : clocks) cfg.clocks.push_back(spec(c));
    std::string error;
    auto n = SimNode::create(cfg, error);
    EXPECT_TRUE(n) << error;
    return n;
}

// Frames of the log whose GridConnect text contains part.
std::size_t count_frames(const SimNetwork& net, const std::string& part) {
    std::size_t n = 0;
    for (const auto& f : net.log_text()) n += f.find(part) != std::string::npos ? 1 : 0;
    return n;
}

TEST(SimNodeClock, DisplaysFollowTheGeneratorOfAnotherNode) {
    SimNetwork net;
    auto master = node(NodeId{0x050101012200ull},
                       {"generator default-fast rate=60 time=1955-07-04T06:00",
                        "generator alternate-1 rate=4 time=1955-07-04T17:00 stopped"});
    auto display =
        node(NodeId{0x050101012201ull}, {"consumer default-fast", "consumer alternate-1"});
    ASSERT_TRUE(master && display);
    net.add_stack(master->stack());
    net.add_stack(display->stack());
    net.start_all();
    net.run_for(10s);
    ASSERT_EQ(display->clocks().size(), 2u);
    const BroadcastClock& fast = display->clocks()[0];
    const BroadcastClock& alt = display->clocks()[1];
    EXPECT_TRUE(fast.running());
    EXPECT_EQ(fast.rate_quarters(), 240);
    const auto want = master->clocks()[0].time_at(net.now());
    const auto got = fast.time_at(net.now());
    EXPECT_LT(got > want ? got - want : want - got, 1min) << fast_time_text(got);
    EXPECT_FALSE(alt.running());
    EXPECT_EQ(fast_time_text(alt.time_at(net.now())), "1955-07-04 17:00");
    // The master announced both clocks' ranges; the displays asked each clock once.
    EXPECT_EQ(count_frames(net, "19524343N010100000100FFFF"), 1u);  // Producer Range, fast
    EXPECT_GE(count_frames(net, "N010100000102FFFF"), 2u);          // ranges of Alternate 1
    EXPECT_TRUE(master->served_protocols().has(Protocol::kEventExchange));
}

TEST(SimNodeClock, ARestartKeepsTheTimeAndAnnouncesTheClockAgain) {
    SimNetwork net;
    auto master =
        node(NodeId{0x050101012200ull}, {"generator default-fast rate=60 time=1955-07-04T06:00"});
    ASSERT_TRUE(master);
    net.add_stack(master->stack());
    net.start_all();
    net.run_for(5s);
    const std::size_t ranges = count_frames(net, "010100000100FFFF");
    master->reboot(net.now());
    net.run_for(1s);
    EXPECT_EQ(count_frames(net, "010100000100FFFF"), 2 * ranges);
    // About six fast minutes passed since 06:00, restart or not.
    const std::string t = fast_time_text(master->clocks()[0].time_at(net.now()));
    EXPECT_EQ(t.substr(0, 15), "1955-07-04 06:0") << t;
}

}  // namespace
}  // namespace olcb::simnode
