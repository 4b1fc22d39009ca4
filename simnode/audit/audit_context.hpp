// What the watches of the client audit share: simnode's nodes and the aliases they hold, the
// connections and the client aliases seen on them, and the log findings go to.
#pragma once

#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <unordered_map>
#include <utility>
#include <vector>

#include "openlcb/can_frame.hpp"
#include "openlcb/clock.hpp"
#include "openlcb/node_id.hpp"
#include "simnode/audit/audit_rule.hpp"
#include "simnode/audit/finding.hpp"
#include "simnode/audit/node_profile.hpp"

namespace olcb::simnode::audit {

/// Where a connection's frames come from, which decides what the audit may assume of them.
enum class ConnectionKind : std::uint8_t {
    kHubClient,  ///< a TCP client of simnode's hub: seen from its first frame on
    kBridge,     ///< a bridged bus (connect, socketcan, serial): its nodes may predate simnode
};

/// The shared state of one audit.
class AuditContext {
public:
    /// A context whose findings count their time from start.
    explicit AuditContext(TimePoint start) : log_(start) {}

    /// The findings.
    FindingLog& log() { return log_; }
    /// The findings.
    const FindingLog& log() const { return log_; }

    /// Adds one of simnode's nodes; a node with the same ID (removed and added again, perhaps
    /// with another CDI) is replaced.
    void add_node(NodeProfile profile);
    /// The index of the node with this ID, or nullopt when it is none of simnode's.
    std::optional<std::size_t> node_index(NodeId id) const;
    /// Records that node `index` now holds alias.
    void set_node_alias(std::uint16_t alias, std::size_t index) { node_by_alias_[alias] = index; }
    /// Forgets a node's alias (it sent AMR).
    void release_node_alias(std::uint16_t alias) { node_by_alias_.erase(alias); }
    /// The node holding alias, or null when no node of simnode's does.
    const NodeProfile* node_at(std::uint16_t alias) const;

    /// Names a connection (a hub client's "HOST:PORT", or a bridge's description).
    void name_connection(std::uint64_t connection, std::string remote, ConnectionKind kind);
    /// The kind of a connection; one never named is a bridge (nothing assumed of its start).
    ConnectionKind kind(std::uint64_t connection) const;
    /// Records that a client alias sent a frame on connection.
    void note_client(std::uint16_t alias, std::uint64_t connection);
    /// Records the node ID a client alias stands for.
    void set_client_node_id(std::uint16_t alias, NodeId id);
    /// The client aliases last seen on connection.
    std::vector<std::uint16_t> clients_of(std::uint64_t connection) const;
    /// The connection client alias was last seen on, if the audit knows the alias.
    std::optional<std::uint64_t> connection_of(std::uint16_t alias) const;
    /// Forgets a client alias (its connection ended).
    void forget_client(std::uint16_t alias) { clients_.erase(alias); }

    /// Records a finding of rule about client alias (and the node at node_alias, when it is one
    /// of simnode's) with the frames involved; key tells apart findings of one rule that are not
    /// repeats of each other (e.g. the variable written).
    void report(RuleId rule, std::uint16_t client_alias, std::optional<std::uint16_t> node_alias,
                std::string message, std::span<const CanFrame> frames, std::string_view key,
                TimePoint now);

private:
    struct Client {
        std::uint64_t connection = 0;
        std::optional<NodeId> node_id;
    };
    struct Connection {
        std::string remote;
        ConnectionKind kind = ConnectionKind::kBridge;
    };

    FindingLog log_;
    std::vector<NodeProfile> nodes_;
    std::unordered_map<std::uint16_t, std::size_t> node_by_alias_;
    std::unordered_map<std::uint64_t, Connection> connections_;
    std::unordered_map<std::uint16_t, Client> clients_;
};

/// The key of a (client alias, node alias) pair in the watches' maps.
constexpr std::uint32_t pair_key(std::uint16_t client, std::uint16_t node) {
    return std::uint32_t{client} << 16 | node;
}
/// The client alias of a pair key.
constexpr std::uint16_t pair_client(std::uint32_t key) {
    return static_cast<std::uint16_t>(key >> 16);
}
/// The node alias of a pair key.
constexpr std::uint16_t pair_node(std::uint32_t key) {
    return static_cast<std::uint16_t>(key & 0xFFFF);
}

/// "0x12C": an alias as findings name it.
std::string alias_text(std::uint16_t alias);

}  // namespace olcb::simnode::audit
