// Shared fixtures of the node-stack tests: the worked-example node on a SimNetwork with a raw
// GridConnect test port (alias 0x12C, like the fact sheet's runner).
#pragma once

#include <gtest/gtest.h>

#include <chrono>
#include <memory>
#include <string>
#include <vector>

#include "openlcb/gc_test_util.hpp"
#include "openlcb/gridconnect.hpp"
#include "openlcb/node_stack.hpp"
#include "openlcb/sim_network.hpp"

namespace olcb::test {

/// The worked example's PSR flags: Datagram, MemCfg, Events; ACDI, SNIP, CDI.
inline ProtocolSet example_protocols() {
    return {Protocol::kDatagram,      Protocol::kMemoryConfiguration,
            Protocol::kEventExchange, Protocol::kAcdi,
            Protocol::kSnip,          Protocol::kCdi};
}

/// Config of a stack for node with the worked example's protocols.
inline NodeStackConfig stack_config(NodeId node = kNodeId) {
    NodeStackConfig c;
    c.node_id = node;
    c.protocols = example_protocols();
    return c;
}

/// A SimNetwork with one raw port that records what it receives as GridConnect text.
class NetFixture : public ::testing::Test {
protected:
    NetFixture()
        : port_(net_.add_endpoint([this](const CanFrame& f, TimePoint) {
              received_.push_back(gridconnect::format(f));
          })) {}

    /// Sends a GridConnect frame from the raw port, delivers everything due now and then runs
    /// the simulated clock for `run`.
    void inject(std::string_view text,
                std::chrono::milliseconds run = std::chrono::milliseconds(0)) {
        port_.send(gc(text));
        net_.run_for(run);
    }
    /// What the raw port received since the last call.
    std::vector<std::string> take() { return std::exchange(received_, {}); }

    SimNetwork net_;
    Transport& port_;
    std::vector<std::string> received_;
};

/// A stack with a config of its own on a network of its own, next to a raw port that records
/// what it receives as GridConnect text: for a test whose stack the fixtures cannot build.
struct LoneStack {
    explicit LoneStack(const NodeStackConfig& config)
        : stack(config), port(net.add_endpoint([this](const CanFrame& f, TimePoint) {
              seen.push_back(gridconnect::format(f));
          })) {
        net.add_stack(stack);
    }
    /// Starts the stack and runs the simulated clock past its reservation.
    void start() {
        net.start_all();
        net.run_for(std::chrono::milliseconds(300));
    }
    /// Sends a GridConnect frame from the raw port and runs the simulated clock for `run`.
    void inject(std::string_view text,
                std::chrono::milliseconds run = std::chrono::milliseconds(0)) {
        port.send(gc(text));
        net.run_for(run);
    }

    SimNetwork net;
    NodeStack stack;
    std::vector<std::string> seen;
    Transport& port;
};

/// One NodeStack on the simulated network next to the raw port.
class StackFixture : public NetFixture {
protected:
    explicit StackFixture(NodeStackConfig config = stack_config()) : stack_(config) {
        net_.add_stack(stack_);
    }
    /// Starts the node and runs past its reservation; clears what the port saw.
    void boot() {
        stack_.start(net_.now());
        ASSERT_TRUE(net_.run_until([&] { return stack_.initialized(); }, std::chrono::seconds(1)));
        net_.run_for(std::chrono::milliseconds(0));
        take();
    }

    NodeStack stack_;
};

/// The worked example's node (alias 0x343) and runner (alias 0x12C) on one network, both
/// started and past their reservation, the log cleared.
class PairFixture : public ::testing::Test {
protected:
    PairFixture() : node_(stack_config(kNodeId)), runner_(stack_config(kRunnerId)) {
        net_.add_stack(node_);
        net_.add_stack(runner_);
        net_.start_all();
        EXPECT_TRUE(net_.run_until([&] { return node_.initialized() && runner_.initialized(); },
                                   std::chrono::seconds(1)));
        net_.run_for(std::chrono::milliseconds(0));
        net_.clear_log();
    }

    SimNetwork net_;
    NodeStack node_;
    NodeStack runner_;
};

}  // namespace olcb::test
