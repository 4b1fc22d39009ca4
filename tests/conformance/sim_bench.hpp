// A Session on a SimNetwork with one simnode under test, for the session and protocol check
// suites: faults by name, the default scenario's CDI unless another is given.
#pragma once

#include <gtest/gtest.h>

#include <filesystem>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "conformance/checks/protocol_checks.hpp"
#include "conformance/conform_test_util.hpp"
#include "conformance/link/link.hpp"
#include "conformance/link/session.hpp"
#include "memory/memory_config_codec.hpp"
#include "openlcb/datagram_defs.hpp"
#include "openlcb/node_stack.hpp"
#include "openlcb/sim_network.hpp"
#include "simnode/faults.hpp"
#include "simnode/sim_node.hpp"

namespace olcb::conform::testing {

/// The default scenario's CDI text.
inline std::string default_cdi() {
    return read_text(std::filesystem::path(OLCB_SOURCE_DIR) / "scenarios/default.xml");
}

/// The io-board scenario's CDI text.
inline std::string io_board_cdi() {
    return read_text(std::filesystem::path(OLCB_SOURCE_DIR) / "scenarios/io-board.xml");
}

/// One simnode (kDut) and the runner's session (kTool) on a simulated segment.
struct SimBench {
    SimNetwork net;
    std::unique_ptr<simnode::SimNode> dut;
    std::unique_ptr<Link> link;
    std::unique_ptr<Session> session;

    /// A node with faults (simnode names) serving cdi (default: scenarios/default.xml), with
    /// stream support unless streams is false.
    explicit SimBench(const std::vector<std::string>& faults = {}, std::string cdi = {},
                      bool streams = true) {
        std::string error;
        simnode::NodeConfig cfg;
        cfg.node_id = kDut;
        cfg.cdi = cdi.empty() ? default_cdi() : std::move(cdi);
        cfg.user_name = "simnode default";
        cfg.streams = streams;
        auto fs = simnode::parse_faults(faults, error);
        EXPECT_TRUE(fs) << error;
        if (fs) cfg.faults = *fs;
        dut = simnode::SimNode::create(cfg, error);
        EXPECT_TRUE(dut) << error;
        if (dut) attach(false);
    }

    /// The node config makes on the segment (frames logged when logging); nullptr with error
    /// set when simnode refuses the config (a CDI it cannot serve).
    static std::unique_ptr<SimBench> serve(const simnode::NodeConfig& config, std::string& error,
                                           bool logging = false) {
        auto dut = simnode::SimNode::create(config, error);
        if (!dut) return nullptr;
        return std::unique_ptr<SimBench>(new SimBench(std::move(dut), logging));
    }

    /// Starts our node and finds the node under test.
    std::optional<NodeInfo> start() {
        EXPECT_TRUE(session->start());
        auto node = session->find_node(dut->node_id());
        EXPECT_TRUE(node);
        return node;
    }

    /// Every protocol check against the node (empty when it was not found).
    std::vector<CheckResult> run(CheckContext& ctx) {
        auto node = start();
        if (!node) return {};
        return run_protocol_checks(*session, *node, ProtocolOptions{}, ctx);
    }

    /// Sends Reset/Reboot and waits until the node announced Initialization Complete again.
    bool reboot(const NodeInfo& node) {
        const std::uint32_t before = session->track(node.id).initializations;
        static constexpr std::uint8_t kReset[] = {0x20, 0xA9};
        session->command(node, kReset);
        return link->run_until([&] { return session->track(node.id).initializations > before; },
                               std::chrono::seconds(2));
    }

private:
    SimBench(std::unique_ptr<simnode::SimNode> node, bool logging) : dut(std::move(node)) {
        attach(logging);
    }

    void attach(bool logging) {
        net.set_logging(logging);
        net.add_stack(dut->stack());
        dut->stack().start(net.now());
        link = make_sim_link(net, kTool);
        session = std::make_unique<Session>(*link);
    }
};

/// A bare node on net whose memory-configuration answers a test writes (a node unlike simnode).
struct ScriptedNode {
    /// Datagram Rejected with reject when non-zero; else Datagram Received OK and reply, if any.
    struct Answer {
        std::uint16_t reject = 0;
        std::vector<std::uint8_t> reply;
    };
    /// Decides the answer to each datagram (unset: reject 0x1041).
    std::function<Answer(const memory::Message&)> answer;
    NodeStack stack;

    /// Node id on net, started now; it serves datagrams and memory configuration only.
    ScriptedNode(SimNetwork& net, NodeId id) : stack(config(id)) {
        stack.set_datagram_handler([this](const ReceivedDatagram& d) {
            const memory::DecodeResult asked = memory::decode(d.payload);
            Answer a = answer && asked.ok() ? answer(asked.message) : Answer{0x1041, {}};
            if (a.reject != 0) {
                stack.reject_datagram(d.source_alias, a.reject);
                return;
            }
            stack.accept_datagram(d.source_alias, datagram::ok_flags(!a.reply.empty()));
            if (!a.reply.empty()) stack.send_datagram(d.source_alias, a.reply, stack.now());
        });
        net.add_stack(stack);
        stack.start(net.now());
    }

private:
    static NodeStackConfig config(NodeId id) {
        NodeStackConfig c;
        c.node_id = id;
        c.protocols = ProtocolSet{Protocol::kDatagram, Protocol::kMemoryConfiguration};
        return c;
    }
};

/// The check with this ID (nullptr when absent).
inline const CheckResult* find_check(const std::vector<CheckResult>& results,
                                     const std::string& id) {
    for (const auto& r : results)
        if (r.id == id) return &r;
    return nullptr;
}

/// Every result, one per line, for failure messages.
inline std::string dump(const std::vector<CheckResult>& results) {
    std::string s;
    for (const auto& r : results) {
        s += std::string(status_name(r.status)) + " " + r.id + " [" +
             std::string(category_name(r.category)) + "] " + r.message;
        if (r.status == Status::kFail) s += " expected=" + r.expected + " seen=" + r.seen;
        s += "\n";
    }
    return s;
}

/// The check with this ID, expected with this status (a placeholder result when absent).
inline const CheckResult& expect_status(const std::vector<CheckResult>& results,
                                        const std::string& id, Status status) {
    static const CheckResult missing = [] {
        CheckResult c;
        c.id = "(missing)";
        return c;
    }();
    const CheckResult* c = find_check(results, id);
    EXPECT_NE(c, nullptr) << id << "\n" << dump(results);
    if (!c) return missing;
    EXPECT_EQ(c->status, status) << id << "\n" << dump(results);
    return *c;
}

/// True when part occurs in text.
inline bool contains(const std::string& text, const std::string& part) {
    return text.find(part) != std::string::npos;
}

/// A bare NodeStack as the node under test: what it answers is what the test makes it answer.
struct FakeBench {
    SimNetwork net;
    NodeStack node;
    std::unique_ptr<Link> link;
    std::unique_ptr<Session> session;

    explicit FakeBench(NodeStackConfig config) : node(config) {
        net.set_logging(false);
        net.add_stack(node);
        node.start(net.now());
        link = make_sim_link(net, kTool);
        session = std::make_unique<Session>(*link);
    }
    /// Starts our node and finds the fake.
    std::optional<NodeInfo> start() {
        EXPECT_TRUE(session->start());
        auto n = session->find_node(kDut);
        EXPECT_TRUE(n);
        return n;
    }
};

/// The fake's configuration: kDut with these protocols.
inline NodeStackConfig fake_config(ProtocolSet protocols = ProtocolSet{Protocol::kDatagram}) {
    NodeStackConfig c;
    c.node_id = kDut;
    c.protocols = protocols;
    return c;
}

}  // namespace olcb::conform::testing
