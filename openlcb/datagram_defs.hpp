// Datagram transport constants (fact sheet 4): sizes, content types, Datagram Received OK flags.
#pragma once

#include <chrono>
#include <cstddef>
#include <cstdint>
#include <optional>

namespace olcb::datagram {

/// Largest datagram payload (content type byte included).
inline constexpr std::size_t kMaxSize = 72;
/// Content bytes per CAN frame.
inline constexpr std::size_t kBytesPerFrame = 8;

/// Allocated content types (datagram byte 0).
enum class ContentType : std::uint8_t {
    kLogRequest = 0x01,
    kLogReply = 0x02,
    kMemoryConfiguration = 0x20,
    kRemoteButton = 0x21,
    kDisplay = 0x28,
    kTrainControl = 0x30,
};

/// True when byte 0 starts a two-byte content type ID (0xE0-0xEF).
constexpr bool is_two_byte_type(std::uint8_t byte0) {
    return (byte0 & 0xF0) == 0xE0;
}
/// True when byte 0 starts a six-byte content type ID (0xF0-0xFF).
constexpr bool is_six_byte_type(std::uint8_t byte0) {
    return (byte0 & 0xF0) == 0xF0;
}

/// Datagram Received OK flag: a reply datagram/message will follow.
inline constexpr std::uint8_t kReplyPending = 0x80;
/// Datagram Received OK: low nibble N, reply within 2^N seconds (0 = not stated).
inline constexpr std::uint8_t kTimeoutExponentMask = 0x0F;

/// Flags byte of a Datagram Received OK; exponent is clamped to 0..15.
constexpr std::uint8_t ok_flags(bool reply_pending, std::uint8_t timeout_exponent = 0) {
    return static_cast<std::uint8_t>((reply_pending ? kReplyPending : 0) |
                                     (timeout_exponent > 15 ? 15 : timeout_exponent));
}
/// True when the flags announce a reply.
/// The reply timeout a Datagram Received OK announces: the reply within 2^N s (0: none given).
constexpr std::uint8_t timeout_exponent(std::uint8_t flags) {
    return static_cast<std::uint8_t>(flags & 0x0F);
}

constexpr bool is_reply_pending(std::uint8_t flags) {
    return (flags & kReplyPending) != 0;
}
/// Announced reply time 2^N s, or nullopt when N = 0 (not stated).
constexpr std::optional<std::chrono::seconds> reply_timeout(std::uint8_t flags) {
    const unsigned n = flags & kTimeoutExponentMask;
    if (n == 0) return std::nullopt;
    return std::chrono::seconds(1u << n);
}

}  // namespace olcb::datagram
