// candump -L log lines, `(1700000000.123456) vcan0 19490343#0501010122`, replayable by canplayer.
#pragma once

#include <chrono>
#include <optional>
#include <string>
#include <string_view>

#include "openlcb/can_frame.hpp"

namespace olcb::candump {

/// One candump -L line: when, on which interface, which frame.
struct Entry {
    std::chrono::microseconds timestamp{0};  ///< since the Unix epoch
    std::string interface;
    CanFrame frame;
};

/// Longest interface name accepted (Linux IFNAMSIZ - 1).
inline constexpr std::size_t kMaxInterfaceName = 15;

/// Formats `(sssssssssss.uuuuuu) iface ID#DATA`, no newline: 8 ID digits for extended frames, 3
/// for standard ones, uppercase hex, `#R` (plus the length digit when non-zero) for remote frames.
std::string format(const CanFrame& frame, std::chrono::microseconds timestamp,
                   std::string_view interface);

/// Parses one candump -L line (trailing whitespace allowed); nullopt for anything else, including
/// CAN FD (`##`), error frames and IDs or lengths out of range.
std::optional<Entry> parse(std::string_view line);

}  // namespace olcb::candump
