#include "openlcb/alias_cache.hpp"

namespace olcb {

void AliasCache::add(std::uint16_t alias, NodeId node) {
    alias &= 0xFFF;
    if (alias == 0 || node.is_zero()) return;
    if (by_alias_.empty()) by_alias_.assign(4096, 0);
    // Every Verified/AMD/Initialization Complete re-announces a known mapping; with 1,000 nodes
    // on a segment, re-inserting it each time dominated start-up (hash node freed and allocated).
    if (by_alias_[alias] == node.value()) return;
    remove_alias(alias);
    if (auto it = by_node_.find(node); it != by_node_.end()) {
        by_alias_[it->second] = 0;
        by_node_.erase(it);
    }
    by_alias_[alias] = node.value();
    by_node_[node] = alias;
}

void AliasCache::remove_alias(std::uint16_t alias) {
    alias &= 0xFFF;
    if (by_alias_.empty() || by_alias_[alias] == 0) return;
    by_node_.erase(NodeId(by_alias_[alias]));
    by_alias_[alias] = 0;
}

void AliasCache::clear() {
    by_alias_.clear();
    by_node_.clear();
}

std::optional<NodeId> AliasCache::node_of(std::uint16_t alias) const {
    alias &= 0xFFF;
    if (by_alias_.empty() || by_alias_[alias] == 0) return std::nullopt;
    return NodeId(by_alias_[alias]);
}

std::optional<std::uint16_t> AliasCache::alias_of(NodeId node) const {
    if (auto it = by_node_.find(node); it != by_node_.end()) return it->second;
    return std::nullopt;
}

}  // namespace olcb
