// StackDriver on a real io_context: stacks over an InProcessBus exchange messages in real time.
// Every run is bounded by a wall-clock limit; no sleeps.
#include "openlcb/stack_driver.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <functional>

#include "openlcb/in_process_bus.hpp"
#include "openlcb/node_test_util.hpp"
#include "openlcb/tcp_hub_server.hpp"
#include "openlcb/tcp_test_util.hpp"

namespace olcb {
namespace {

using namespace std::chrono_literals;
using namespace test;

// The worked example's node and runner, each on a driver of its own over its own transport.
struct DrivenPair {
    DrivenPair(boost::asio::io_context& io, Transport& node_port, Transport& runner_port)
        : node_driver(io, node_port), runner_driver(io, runner_port) {
        node_driver.attach(node);
        runner_driver.attach(runner);
    }
    /// Starts both and runs io until both are initialized.
    bool start(boost::asio::io_context& io) {
        node_driver.start_all();
        runner_driver.start_all();
        return run_until(
            io, [&] { return node.initialized() && runner.initialized(); }, 2s);
    }
    NodeStack node{stack_config(kNodeId)};
    NodeStack runner{stack_config(kRunnerId)};
    StackDriver node_driver;
    StackDriver runner_driver;
};

// The node and runner on one driver over an InProcessBus whose other endpoint records what
// leaves the driver as GridConnect text.
struct SharedDriver {
    SharedDriver() {
        bus.add_endpoint([this](const CanFrame& f) { outside.push_back(gridconnect::format(f)); });
        driver.attach(node);
        driver.attach(runner);
    }
    /// Starts both and runs io until both are initialized.
    bool start() {
        driver.start_all();
        return run_until(
            io, [&] { return node.initialized() && runner.initialized(); }, 2s);
    }
    boost::asio::io_context io;
    InProcessBus bus{io};
    std::vector<std::string> outside;
    NodeStack node{stack_config(kNodeId)};
    NodeStack runner{stack_config(kRunnerId)};
    StackDriver driver{io, bus.add_endpoint()};
};

TEST(StackDriver, TwoStacksOnTwoBusPortsExchangeVerifyNodeId) {
    boost::asio::io_context io;
    InProcessBus bus(io);
    DrivenPair pair(io, bus.add_endpoint(), bus.add_endpoint());
    auto& [node, runner, node_driver, runner_driver] = pair;
    std::vector<Message> heard;
    runner.set_message_handler([&](const Message& m) {
        if (m.mti == Mti::kVerifiedNodeId) heard.push_back(m);
        return true;
    });
    const auto started = std::chrono::steady_clock::now();
    ASSERT_TRUE(pair.start(io));
    EXPECT_GE(std::chrono::steady_clock::now() - started, 200ms) << "RID waits 200 ms";
    Message verify;
    verify.mti = Mti::kVerifyNodeIdGlobal;
    EXPECT_EQ(runner.send_message(verify), SendStatus::kSent);  // outside any driver callback
    ASSERT_TRUE(run_until(
        io, [&] { return !heard.empty(); }, 2s));
    EXPECT_EQ(heard[0].source, (NodeHandle{kNodeId, 0x343}));
    EXPECT_EQ(heard[0].payload, (std::vector<std::uint8_t>{5, 1, 1, 1, 0x22, 0}));
    EXPECT_GE(node_driver.stats().timer_arms, 1u);
    EXPECT_GE(node_driver.stats().polls, 1u);
}

TEST(StackDriver, StacksOnOneDriverShareTheSegmentAndTheTransportSeesTheirFrames) {
    SharedDriver shared;
    auto& [io, bus, outside, node, runner, driver] = shared;
    EXPECT_EQ(driver.size(), 2u);
    ASSERT_TRUE(shared.start());
    EXPECT_EQ(node.alias_cache().alias_of(kRunnerId), 0x12C) << "saw the other stack's AMD";
    // The runner asks the node directly: the frames never leave the driver to come back.
    std::vector<Message> heard;
    runner.set_message_handler([&](const Message& m) {
        if (m.mti == Mti::kProtocolSupportReply) heard.push_back(m);
        return true;
    });
    Message psi;
    psi.mti = Mti::kProtocolSupportInquiry;
    psi.destination = NodeHandle{kNodeId, 0};
    EXPECT_EQ(runner.send_message(psi), SendStatus::kSent);
    ASSERT_TRUE(run_until(
        io, [&] { return !heard.empty(); }, 2s));
    EXPECT_EQ(heard[0].payload, (std::vector<std::uint8_t>{0x54, 0x58, 0, 0, 0, 0}));
    ASSERT_TRUE(run_until(
        io, [&] { return outside.size() >= 16u; }, 2s));
    EXPECT_EQ(outside[14], ":X1982812CN0343;");
    EXPECT_EQ(outside[15], ":X19668343N012C545800000000;");
    // A frame from outside reaches both stacks.
    bus.add_endpoint().send(gc(":X10702999N;"));  // global AME: both answer with AMD
    ASSERT_TRUE(run_until(
        io, [&] { return outside.size() >= 19u; }, 2s));
    EXPECT_EQ(driver.stats().frames_in, 1u);
}

TEST(StackDriver, WorksOnHubLocalEndpointsThatRelaySynchronously) {
    boost::asio::io_context io;
    TcpHubServer hub(io);
    DrivenPair pair(io, hub.add_local_endpoint(), hub.add_local_endpoint());
    auto& [node, runner, node_driver, runner_driver] = pair;
    std::vector<ReceivedDatagram> got;
    node.set_datagram_handler([&](const ReceivedDatagram& d) {
        got.push_back(d);
        node.accept_datagram(d.source_alias);
    });
    std::vector<DatagramOutcome> outcomes;
    runner.set_outcome_handler([&](const DatagramOutcome& o) { outcomes.push_back(o); });
    ASSERT_TRUE(pair.start(io));
    const std::vector<std::uint8_t> payload(20, 0x20);
    ASSERT_TRUE(runner.send_datagram(0x343, payload, Clock::now()).has_value());
    ASSERT_TRUE(run_until(
        io, [&] { return !outcomes.empty(); }, 2s));
    EXPECT_EQ(outcomes[0].status, DatagramOutcome::Status::kAccepted);
    ASSERT_EQ(got.size(), 1u);
    EXPECT_EQ(got[0].payload, payload);
}

TEST(StackDriver, OwnerTimerScheduledOutsideCallbacksFiresOnTime) {
    boost::asio::io_context io;
    InProcessBus bus(io);
    NodeStack node(stack_config(kNodeId));
    StackDriver driver(io, bus.add_endpoint());
    driver.attach(node);
    driver.start_all();
    ASSERT_TRUE(run_until(
        io, [&] { return node.initialized(); }, 2s));
    io.poll();  // let the driver settle: no deadline left, timer idle
    std::optional<TimePoint> fired;
    const TimePoint due = Clock::now() + 30ms;
    node.schedule(due, [&](TimePoint now) { fired = now; });
    ASSERT_TRUE(run_until(
        io, [&] { return fired.has_value(); }, 2s));
    EXPECT_GE(*fired, due);
}

TEST(StackDriver, DetachedStackIsNoLongerDriven) {
    boost::asio::io_context io;
    InProcessBus bus(io);
    NodeStack node(stack_config(kNodeId));
    {
        StackDriver driver(io, bus.add_endpoint());
        driver.attach(node);
        driver.detach(node);
        EXPECT_EQ(driver.size(), 0u);
        node.start(Clock::now());
        io.poll();
        EXPECT_TRUE(node.has_output()) << "nobody pumps a detached stack";
    }
    io.poll();  // posted work of the destroyed driver must be harmless
}

TEST(StackDriver, FlushDeliversPendingOutputAtOnce) {
    SharedDriver shared;
    auto& [io, bus, outside, node, runner, driver] = shared;
    ASSERT_TRUE(shared.start());
    io.poll();
    ASSERT_EQ(runner.alias_cache().alias_of(kNodeId), 0x343);
    node.release(Clock::now());
    driver.flush();
    EXPECT_FALSE(node.has_output()) << "flush() took the AMR";
    driver.detach(node);
    EXPECT_FALSE(runner.alias_cache().alias_of(kNodeId)) << "the other stack saw the AMR";
    const std::string amr = ":X10703343N050101012200;";
    EXPECT_TRUE(run_until(
        io, [&] { return std::find(outside.begin(), outside.end(), amr) != outside.end(); }, 2s))
        << "the transport got the AMR";
}

}  // namespace
}  // namespace olcb
