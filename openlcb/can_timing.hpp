// CAN bit timing: how long one frame occupies the bus. The one model of every paced segment
// (InProcessBus with enable_timing(), BusPacer, the TCP hub's --bitrate).
#pragma once

#include <chrono>
#include <cstdint>

namespace olcb {

/// The bit rate of an OpenLCB CAN segment (CanPhysicalS).
inline constexpr std::uint32_t kLccBitrate = 125'000;

/// Worst-case bit count on the wire of one 29-bit data frame with `len` (0..8) data bytes.
///
/// Fields before the CRC delimiter are subject to stuffing: SOF 1 + base ID 11 + SRR 1 + IDE 1 +
/// extended ID 18 + RTR 1 + r1 1 + r0 1 + DLC 4 + data 8n + CRC 15 = 54 + 8n bits. Worst case,
/// one stuff bit follows the first 5 equal bits and then every 4 further bits:
/// floor((54 + 8n - 1) / 4). Unstuffed tail: CRC delimiter 1 + ACK slot 1 + ACK delimiter 1 +
/// EOF 7 + intermission 3 = 13. Total = 54 + 8n + 13 + floor((53 + 8n) / 4); 80 bits for n = 0,
/// 160 bits for n = 8 (Davis et al., "CAN schedulability analysis: refuted, revisited", 2007).
constexpr std::uint32_t can_frame_bits(std::uint8_t len) {
    const std::uint32_t n = len > 8 ? 8 : len;
    const std::uint32_t stuffed = 54 + 8 * n;
    return stuffed + 13 + (stuffed - 1) / 4;
}

/// Time one worst-case 29-bit frame of `len` data bytes occupies a bus running at `bitrate` bit/s.
constexpr std::chrono::nanoseconds can_frame_time(std::uint8_t len, std::uint32_t bitrate) {
    return std::chrono::nanoseconds(std::uint64_t{can_frame_bits(len)} * 1'000'000'000ull /
                                    (bitrate == 0 ? 1 : bitrate));
}

}  // namespace olcb
