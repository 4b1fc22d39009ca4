// The simulated CAN segment (openlcb/sim_network.cpp): bus timing, 1,000 stacks allocating
// distinct aliases, the same log for the same inputs, a clock that jumps exactly, the bound on
// same-instant ping-pong, and raw endpoints.
#include "openlcb/sim_network.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <deque>
#include <set>
#include <string>
#include <vector>

#include "openlcb/node_test_util.hpp"

namespace olcb {
namespace {

using namespace std::chrono_literals;
using namespace test;

// Node IDs whose first TN aliases all collide: the low two 12-bit groups are equal, so they
// cancel in the XOR and every node starts with alias 0x050 ^ 0x101 = 0x151.
NodeId colliding_id(std::uint32_t i) {
    return NodeId(0x050101000000ull | i << 12 | i);
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
