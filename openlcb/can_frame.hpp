// A CAN 2.0 frame as every layer of the stack sees it: the wire unit of OpenLCB-CAN.
#pragma once

#include <algorithm>
#include <array>
#include <cstdint>

namespace olcb {

/// One CAN frame: 29-bit (extended) or 11-bit identifier, 0-8 data bytes, data or remote.
struct CanFrame {
    std::uint32_t id = 0;  ///< 29-bit ID when extended, 11-bit otherwise
    std::uint8_t len = 0;  ///< number of valid bytes in data (0..8)
    std::array<std::uint8_t, 8> data{};
    bool extended = true;  ///< OpenLCB uses only extended frames
    bool remote = false;   ///< RTR frame: OpenLCB nodes ignore these

    /// Equal when ID, kind and the first len bytes agree (bytes past len are ignored).
    friend bool operator==(const CanFrame& a, const CanFrame& b) {
        return a.id == b.id && a.len == b.len && a.extended == b.extended && a.remote == b.remote &&
               std::equal(a.data.begin(), a.data.begin() + a.len, b.data.begin());
    }
};

}  // namespace olcb
