// What this node has learned about other nodes' alias <-> node ID mappings on one CAN segment.
#pragma once

#include <cstddef>
#include <cstdint>
#include <optional>
#include <unordered_map>
#include <vector>

#include "base/node_id.hpp"
#include "openlcb/can_frame.hpp"

namespace olcb {

/// Bidirectional alias <-> node ID map; bounded by the 4095 possible aliases.
class AliasCache {
public:
    /// Records alias <-> node, dropping any older mapping of either side. Alias 0 or a zero node
    /// ID is ignored.
    void add(std::uint16_t alias, NodeId node);
    /// Forgets the mapping of alias (e.g. after AMR).
    void remove_alias(std::uint16_t alias);
    /// Forgets everything (global AME).
    void clear();
    /// Node ID behind alias, if known.
    std::optional<NodeId> node_of(std::uint16_t alias) const;
    /// Alias of node, if known.
    std::optional<std::uint16_t> alias_of(NodeId node) const;
    /// Number of known mappings.
    std::size_t size() const { return by_node_.size(); }
    /// Takes in what one frame of the segment says of the mappings, for an observer of the whole
    /// segment (the cache StackGroup's stacks share): AMD, Initialization Complete and Verified
    /// Node ID announce one, AMR withdraws one, a global AME voids them all. A node's own cache
    /// is kept by its AliasAllocator, which also tells its own ID apart.
    void learn(const CanFrame& frame);

private:
    std::vector<std::uint64_t> by_alias_;  // 4096 slots once used; 0 = unknown
    std::unordered_map<NodeId, std::uint16_t> by_node_;
};

}  // namespace olcb
