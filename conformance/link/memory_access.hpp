// Byte access to one node's memory spaces, the interface the safety backup, the encoding checks,
// the JMRI backups and the restore read and write through (SessionMemory over a Session; tests use
// a fake), and how bytes are shown.
#pragma once

#include <cstddef>
#include <cstdint>
#include <span>
#include <string>
#include <vector>

namespace olcb::conform {

/// Outcome of one memory access.
struct AccessResult {
    bool ok = false;
    std::uint16_t error = 0;         ///< the node's error code when !ok (0x2010 on timeout)
    std::vector<std::uint8_t> data;  ///< read data (may be short at the end of a space)
    /// A write lcc-conform kept back (its ledger's gate refused it): why; the node saw nothing.
    std::string not_sent{};
};

/// Byte access to one node's memory spaces. The runner adapts its Session to it; tests use a fake.
class MemoryAccess {
public:
    virtual ~MemoryAccess() = default;
    /// Reads `count` bytes from (space, address); any count (split into protocol-sized reads).
    virtual AccessResult read(std::uint8_t space, std::uint32_t address, std::size_t count) = 0;
    /// Writes `data` at (space, address); any length (split into protocol-sized writes).
    virtual AccessResult write(std::uint8_t space, std::uint32_t address,
                               std::span<const std::uint8_t> data) = 0;
};

/// Bytes as spaced upper-case hex ("0A 0B"), at most `max` bytes then "...".
std::string hex_bytes(std::span<const std::uint8_t> bytes, std::size_t max = 16);

}  // namespace olcb::conform
