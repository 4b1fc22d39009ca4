// An in-memory node for the encoding/backup tests: spaces of bytes, with optional misbehaviour.
#pragma once

#include <algorithm>
#include <map>
#include <span>
#include <vector>

#include "conformance/link/memory_access.hpp"

namespace olcb::conform::testing {

/// Spaces of bytes; faults reproduce what simnode's faults do to a read-back.
struct FakeMemory : MemoryAccess {
    std::map<std::uint8_t, std::vector<std::uint8_t>> spaces;
    bool drop_writes = false;     ///< acknowledge writes, store nothing
    bool reverse_writes = false;  ///< store each write byte-reversed (byte order faults)
    std::size_t writes = 0;

    AccessResult read(std::uint8_t space, std::uint32_t address, std::size_t count) override {
        auto it = spaces.find(space);
        if (it == spaces.end()) return {false, 0x1081, {}};
        if (address + count > it->second.size()) return {false, 0x1082, {}};
        const auto bytes = std::span(it->second).subspan(address, count);
        return {true, 0, {bytes.begin(), bytes.end()}};
    }
    AccessResult write(std::uint8_t space, std::uint32_t address,
                       std::span<const std::uint8_t> data) override {
        auto it = spaces.find(space);
        if (it == spaces.end()) return {false, 0x1081, {}};
        if (address + data.size() > it->second.size()) return {false, 0x1082, {}};
        ++writes;
        if (drop_writes) return {true, 0, {}};
        std::vector<std::uint8_t> bytes(data.begin(), data.end());
        if (reverse_writes) std::reverse(bytes.begin(), bytes.end());
        std::copy(bytes.begin(), bytes.end(), it->second.begin() + address);
        return {true, 0, {}};
    }
};

}  // namespace olcb::conform::testing
