#include "simnode/audit/audit_context.hpp"

#include <utility>

#include "base/hex.hpp"
#include "openlcb/gridconnect.hpp"

namespace olcb::simnode::audit {

std::string alias_text(std::uint16_t alias) {
    return base::hex(alias, 3);
}

void AuditContext::add_node(NodeProfile profile) {
    // The index stays: the aliases mapped to it now lead to the new profile.
    if (const auto index = node_index(profile.node_id())) {
        nodes_[*index] = std::move(profile);
        return;
    }
    nodes_.push_back(std::move(profile));
}

std::optional<std::size_t> AuditContext::node_index(NodeId id) const {
    for (std::size_t i = 0; i < nodes_.size(); ++i) {
        if (nodes_[i].node_id() == id) return i;
    }
    return std::nullopt;
}

const NodeProfile* AuditContext::node_at(std::uint16_t alias) const {
    const auto it = node_by_alias_.find(alias);
    return it == node_by_alias_.end() ? nullptr : &nodes_[it->second];
}

void AuditContext::name_connection(std::uint64_t connection, std::string remote,
                                   ConnectionKind kind) {
    connections_[connection] = Connection{std::move(remote), kind};
}

ConnectionKind AuditContext::kind(std::uint64_t connection) const {
    const auto it = connections_.find(connection);
    return it == connections_.end() ? ConnectionKind::kBridge : it->second.kind;
}

void AuditContext::note_client(std::uint16_t alias, std::uint64_t connection) {
    clients_[alias].connection = connection;
}

void AuditContext::set_client_node_id(std::uint16_t alias, NodeId id) {
    clients_[alias].node_id = id;
}

std::vector<std::uint16_t> AuditContext::clients_of(std::uint64_t connection) const {
    std::vector<std::uint16_t> out;
    for (const auto& [alias, client] : clients_) {
        if (client.connection == connection) out.push_back(alias);
    }
    return out;
}

std::optional<std::uint64_t> AuditContext::connection_of(std::uint16_t alias) const {
    const auto it = clients_.find(alias);
    if (it == clients_.end()) return std::nullopt;
    return it->second.connection;
}

void AuditContext::report(RuleId rule, std::uint16_t client_alias,
                          std::optional<std::uint16_t> node_alias, std::string message,
                          std::span<const CanFrame> frames, std::string_view key, TimePoint now) {
    Finding f;
    f.rule = rule;
    f.message = std::move(message);
    f.client.alias = client_alias;
    if (const auto it = clients_.find(client_alias); it != clients_.end()) {
        f.client.connection = it->second.connection;
        f.client.node_id = it->second.node_id;
        if (const auto c = connections_.find(it->second.connection); c != connections_.end())
            f.client.remote = c->second.remote;
    }
    if (node_alias) {
        if (const NodeProfile* node = node_at(*node_alias))
            f.node = NodeRef{node->node_id(), *node_alias};
    }
    for (const CanFrame& frame : frames) f.frames.push_back(gridconnect::format(frame));
    log_.add(std::move(f), key, now);
}

}  // namespace olcb::simnode::audit
