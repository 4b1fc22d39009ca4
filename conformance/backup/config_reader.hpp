// Reads the values of a configuration backup from a node: each space's used byte ranges in
// merged reads (64-byte datagrams underneath), not one request per variable.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "conformance/backup/backup_keys.hpp"
#include "conformance/link/memory_access.hpp"

namespace olcb::conform {

/// One variable's value as read from the node.
struct ConfigValue {
    std::optional<std::string> text;  ///< the value (strings unescaped); nullopt when unreadable
    std::string error;                ///< why it could not be read or decoded
};

/// A byte range of one space read in one go.
struct ReadSpan {
    std::uint32_t space = 0;
    std::uint64_t begin = 0;
    std::uint64_t end = 0;
    friend bool operator==(const ReadSpan&, const ReadSpan&) = default;
};

/// The ranges a backup reads: every entry's bytes, sorted by space and address and merged where
/// one read of both costs no more 64-byte reads than two; entries no read can reach are left out.
std::vector<ReadSpan> plan_config_reads(const std::vector<ConfigEntry>& entries);

/// Every entry's value (same order), read through memory in the planned ranges; the entries of
/// a range that fails or ends short are read again one by one, so a bad variable costs only
/// itself.
std::vector<ConfigValue> read_config_values(const std::vector<ConfigEntry>& entries,
                                            MemoryAccess& memory);

}  // namespace olcb::conform
