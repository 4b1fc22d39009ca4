// An OpenLCB message independent of its CAN framing: what handlers consume and produce.
#pragma once

#include <cstdint>
#include <optional>
#include <vector>

#include "base/node_id.hpp"
#include "openlcb/mti.hpp"

namespace olcb {

/// A node as seen on CAN: its node ID and alias, either of which may be unknown (zero).
struct NodeHandle {
    NodeId id;                ///< zero when unknown (e.g. only the alias was on the wire)
    std::uint16_t alias = 0;  ///< zero when unknown (e.g. on a non-CAN link)

    /// Same ID and alias.
    friend bool operator==(const NodeHandle&, const NodeHandle&) = default;
};

/// One OpenLCB message: MTI, source, optional destination and payload bytes. For addressed
/// messages the payload excludes the CAN `fddd` bytes; for datagrams it is the datagram content.
struct Message {
    Mti mti = Mti::kVerifyNodeIdGlobal;
    NodeHandle source;
    std::optional<NodeHandle> destination;  ///< set for addressed messages
    std::vector<std::uint8_t> payload;

    /// Same MTI, endpoints and payload.
    friend bool operator==(const Message&, const Message&) = default;
};

}  // namespace olcb
