// Memory Configuration command payloads (MemoryConfigurationS §4) as a client sends them in a
// datagram: what the audit's frame scripts and the end-to-end suites write to a node.
#pragma once

#include <cstdint>
#include <vector>

namespace olcb::test_support {

/// The command header: 0x20, command, address, then the space byte, or the space folded into
/// the command (short form) for 0xFD..0xFF.
inline std::vector<std::uint8_t> mem_cmd(std::uint8_t command, std::uint8_t space,
                                         std::uint32_t address) {
    std::vector<std::uint8_t> p{0x20,
                                command,
                                static_cast<std::uint8_t>(address >> 24),
                                static_cast<std::uint8_t>(address >> 16),
                                static_cast<std::uint8_t>(address >> 8),
                                static_cast<std::uint8_t>(address)};
    if (space >= 0xFD) {
        p[1] = static_cast<std::uint8_t>(command | (space - 0xFC));
    } else {
        p.push_back(space);
    }
    return p;
}

/// A read of count bytes at address in space.
inline std::vector<std::uint8_t> read_cmd(std::uint8_t space, std::uint32_t address,
                                          std::uint8_t count) {
    auto p = mem_cmd(0x40, space, address);
    p.push_back(count);
    return p;
}

/// A write of data at address in space.
inline std::vector<std::uint8_t> write_cmd(std::uint8_t space, std::uint32_t address,
                                           const std::vector<std::uint8_t>& data) {
    auto p = mem_cmd(0x00, space, address);
    p.insert(p.end(), data.begin(), data.end());
    return p;
}

/// Update Complete.
inline std::vector<std::uint8_t> update_complete_cmd() {
    return {0x20, 0xA8};
}

}  // namespace olcb::test_support
