// What the client audit knows of one of simnode's nodes: its node ID, its served spaces (size,
// read-only) and the variables its CDI lays out in them, which writes are judged against.
#pragma once

#include <cstdint>
#include <map>
#include <memory>
#include <optional>
#include <string>

#include "cdi/document.hpp"
#include "openlcb/node_id.hpp"
#include "simnode/node_memory.hpp"

namespace olcb::simnode {
class SimNode;
}

namespace olcb::simnode::audit {

/// Size and access of one served space.
struct SpaceShape {
    std::uint32_t size = 0;  ///< bytes from address 0 (highest address + 1)
    bool read_only = false;  ///< writes are refused
};

/// One variable a request touches.
struct VariableRef {
    std::uint64_t address = 0;              ///< its first byte
    std::uint64_t size = 0;                 ///< its bytes
    const cdi::Element* element = nullptr;  ///< what it is (never null in a found ref)
    std::string name;                       ///< cdi::variable_name(): "Settings.Port(1).On event"
    /// One past its last byte.
    std::uint64_t end() const { return address + size; }
};

/// A node as the audit sees it. The variables of a space are the CDI's; with <acdi/> the ACDI
/// user strings of space 251 count too where the CDI lays out nothing (CDI §5.1.2).
class NodeProfile {
public:
    /// A profile of node id serving cdi (may be null: no variables) and spaces.
    NodeProfile(NodeId id, std::shared_ptr<const CdiModel> cdi,
                std::map<std::uint8_t, SpaceShape> spaces);

    /// The node's ID.
    NodeId node_id() const { return id_; }
    /// The shape of a served space; nullopt when the node does not serve it.
    std::optional<SpaceShape> space(std::uint8_t number) const;
    /// The variable holding byte (space, address), the first in document order if several do.
    std::optional<VariableRef> variable_at(std::uint8_t space, std::uint64_t address) const;

private:
    NodeId id_;
    std::shared_ptr<const CdiModel> cdi_;
    std::map<std::uint8_t, SpaceShape> spaces_;
};

/// The profile of a SimNode: its CDI model, and its served spaces as built (faults aside: they
/// change what the node does, not what a client may do).
NodeProfile profile_of(const SimNode& node);

}  // namespace olcb::simnode::audit
