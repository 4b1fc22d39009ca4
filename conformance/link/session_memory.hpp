// MemoryAccess over a Session: what the safety backup, the encoding checks and the JMRI backup
// read and write through.
#pragma once

#include <cstddef>
#include <cstdint>
#include <span>

#include "conformance/link/memory_access.hpp"
#include "conformance/link/session.hpp"

namespace olcb::conform {

/// MemoryAccess over a Session: splits reads and writes into 64-byte datagrams; a read goes on
/// after a short reply and ends only at the count, the end of the space or an error.
class SessionMemory : public MemoryAccess {
public:
    /// Access to node's memory through session.
    SessionMemory(Session& session, NodeInfo node) : session_(session), node_(node) {}
    AccessResult read(std::uint8_t space, std::uint32_t address, std::size_t count) override;
    AccessResult write(std::uint8_t space, std::uint32_t address,
                       std::span<const std::uint8_t> data) override;

private:
    Session& session_;
    NodeInfo node_;
};

}  // namespace olcb::conform
