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

/// Node ID of the fact sheet's node under test (first alias 0x343).
inline constexpr NodeId kNodeId{0x05'01'01'01'22'00ull};
/// Node ID of the fact sheet's runner (first alias 0x12C).
inline constexpr NodeId kRunnerId{0x02'01'0D'00'00'01ull};

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
