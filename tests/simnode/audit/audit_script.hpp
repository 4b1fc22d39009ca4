// Fixture of the client audit's rule tests: a ClientAudit fed GridConnect frame scripts on a
// simulated clock. The node is the default one (scenarios/default.xml, node ID
// 05.01.01.01.22.00 on alias 0x343, the fact sheet's); the client is the fact sheet's runner
// (02.01.0D.00.00.01 on alias 0x12C) on hub connection 1.
#pragma once

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cstdint>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include "openlcb/addressed_framing.hpp"
#include "openlcb/can_defs.hpp"
#include "openlcb/gridconnect.hpp"
#include "simnode/audit/client_audit.hpp"
#include "simnode/sim_node.hpp"
#include "simnode/sim_node_test_util.hpp"
#include "support/memory_commands.hpp"

namespace olcb::simnode::audit::test {

using namespace std::chrono_literals;
using simnode::test::kClientAlias;
using simnode::test::kClientId;
using simnode::test::kNodeId;
using test_support::read_cmd;
using test_support::update_complete_cmd;
using test_support::write_cmd;

/// The default node's alias.
inline constexpr std::uint16_t kNodeAlias = 0x343;
/// The client's hub connection.
inline constexpr std::uint64_t kConnection = 1;

/// The default node's profile (built once from a RAM-only SimNode).
inline const NodeProfile& default_profile() {
    static const NodeProfile profile = [] {
        NodeConfig c;
        c.node_id = kNodeId;
        c.cdi = simnode::test::default_cdi();
        std::string error;
        auto node = SimNode::create(std::move(c), error);
        EXPECT_TRUE(node) << error;
        return profile_of(*node);
    }();
    return profile;
}

/// A ClientAudit and the frames both sides send it.
class AuditScript : public ::testing::Test {
protected:
    AuditScript() : audit_(now_) {
        audit_.add_node(default_profile());
        audit_.name_connection(kConnection, "127.0.0.1:50000", ConnectionKind::kHubClient);
        node(":X10701343N050101012200;");  // AMD: the node holds 0x343
        node(":X19100343N050101012200;");  // Initialization Complete
    }

    /// A frame from the node (GridConnect text), now.
    void node(std::string_view text) { feed(text, Direction::kFromNode, 0); }
    /// A frame from the client on connection, now.
    void client(std::string_view text, std::uint64_t connection = kConnection) {
        feed(text, Direction::kFromClient, connection);
    }
    /// Moves the simulated clock on and lets the audit judge what came due.
    void advance(Duration d) {
        now_ += d;
        audit_.poll(now_);
    }
    /// The client reserves alias and maps it to id as CanFrameTransferS §6.2 says (Permitted,
    /// still Uninitialized).
    void reserve(std::uint16_t alias = kClientAlias, NodeId id = kClientId,
                 std::uint64_t connection = kConnection) {
        for (int n = 7; n >= 4; --n) frame_from_client(can::make_cid(n, id, alias), connection);
        advance(200ms);
        frame_from_client(can::make_rid(alias), connection);
        frame_from_client(can::make_amd(alias, id), connection);
    }
    /// The client's Initialization Complete (MessageNetworkS §3.4.1).
    void initialized(std::uint16_t alias = kClientAlias, NodeId id = kClientId,
                     std::uint64_t connection = kConnection) {
        frame_from_client(can::make_node_id_frame(can::message_header(0x100, alias), id),
                          connection);
    }
    /// reserve(), then Initialization Complete: a client as the standards start it.
    void login(std::uint16_t alias = kClientAlias, NodeId id = kClientId,
               std::uint64_t connection = kConnection) {
        reserve(alias, id, connection);
        initialized(alias, id, connection);
    }
    /// A datagram from the client to the node, framed as a real sender frames it.
    void client_datagram(const std::vector<std::uint8_t>& payload,
                         std::uint16_t alias = kClientAlias,
                         std::uint64_t connection = kConnection) {
        for (const CanFrame& f : datagram_frames(alias, kNodeAlias, payload))
            frame_from_client(f, connection);
    }
    /// A datagram from the node to the client.
    void node_datagram(const std::vector<std::uint8_t>& payload) {
        for (const CanFrame& f : datagram_frames(kNodeAlias, kClientAlias, payload))
            audit_.on_frame(f, Direction::kFromNode, 0, now_);
    }
    /// The node's Datagram Received OK with flags (0x80: Reply Pending).
    void node_ok(std::uint8_t flags = 0x80) {
        node(flags == 0 ? ":X19A28343N012C;" : ":X19A28343N012C" + hex(flags) + ";");
    }
    /// The client's Datagram Received OK of a node datagram.
    void client_ok() { client(":X19A2812CN0343;"); }
    /// Ends the run.
    void finish() { audit_.finish(now_); }

    /// The rule names of every finding, in order.
    std::vector<std::string> rules_found() const {
        std::vector<std::string> out;
        for (const Finding& f : audit_.log().findings()) out.emplace_back(rule(f.rule).name);
        return out;
    }
    /// The findings of one rule.
    std::vector<Finding> found(RuleId id) const {
        std::vector<Finding> out;
        for (const Finding& f : audit_.log().findings()) {
            if (f.rule == id) out.push_back(f);
        }
        return out;
    }

    TimePoint now_{};  // before audit_: its start
    ClientAudit audit_;

private:
    static std::string hex(std::uint8_t b) {
        constexpr char kDigits[] = "0123456789ABCDEF";
        return {kDigits[b >> 4], kDigits[b & 15]};
    }
    static std::vector<CanFrame> datagram_frames(std::uint16_t src, std::uint16_t dst,
                                                 const std::vector<std::uint8_t>& payload) {
        Message m;
        m.mti = Mti::kDatagram;
        m.source.alias = src;
        m.destination = NodeHandle{NodeId(), dst};
        m.payload = payload;
        std::vector<CanFrame> frames;
        EXPECT_EQ(encode_message(m, frames), FramingError::kNone);
        return frames;
    }
    void frame_from_client(const CanFrame& f, std::uint64_t connection) {
        audit_.on_frame(f, Direction::kFromClient, connection, now_);
    }
    void feed(std::string_view text, Direction direction, std::uint64_t connection) {
        const auto f = gridconnect::parse_frame(text);
        ASSERT_TRUE(f) << text;
        audit_.on_frame(*f, direction, connection, now_);
    }
};

/// The alias and message rules (alias_watch_test.cpp, client_audit_test.cpp).
class AliasRules : public AuditScript {};

/// The memory and CDI rules (memory_watch_test.cpp, write_judge_test.cpp) against the default
/// node (scenarios/default.xml: space 0xFD is 179 bytes, Enabled @0 1-byte int map 0/1, Trim @1
/// 2-byte int -1000..1000, Mode @15 map 1/2/3, Gain @16 half float 0..4, Label @30 16-byte
/// string, the Port group @46 (4 x 33 bytes), the action @178 value 1; 0xFB lays out the user
/// name @1 and description @64), the client logged in.
class MemoryRules : public AuditScript {
protected:
    MemoryRules() { login(); }

    /// A write and the node's plain OK: each write is its own finished exchange.
    void write(std::uint8_t space, std::uint32_t address, const std::vector<std::uint8_t>& data) {
        client_datagram(write_cmd(space, address, data));
        node_ok(0);
        advance(5ms);
    }
    /// Update Complete and the node's plain OK.
    void update_complete() {
        client_datagram(update_complete_cmd());
        node_ok(0);
    }
    /// s, padded with NULs (or cut) to size bytes.
    static std::vector<std::uint8_t> text(std::string_view s, std::size_t size) {
        std::vector<std::uint8_t> out(s.begin(), s.end());
        out.resize(size, 0);
        return out;
    }
};

}  // namespace olcb::simnode::audit::test
