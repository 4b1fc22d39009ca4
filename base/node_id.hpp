// 48-bit node IDs and 64-bit event IDs: big-endian bytes on the wire, dotted hex for people;
// the one text codec of both.
#pragma once

#include <array>
#include <compare>
#include <cstdint>
#include <functional>
#include <optional>
#include <span>
#include <string>
#include <string_view>

namespace olcb::base {

/// A 48-bit OpenLCB node ID (value 0 means "unknown / none").
class NodeId {
public:
    /// Number of bytes on the wire.
    static constexpr std::size_t kSize = 6;
    /// Mask of the 48 valid bits.
    static constexpr std::uint64_t kMask = 0xFFFF'FFFF'FFFFull;

    /// The zero node ID.
    constexpr NodeId() = default;
    /// Node ID from its numeric value; bits above 47 are discarded.
    constexpr explicit NodeId(std::uint64_t value) : value_(value & kMask) {}

    /// Numeric value (0..2^48-1).
    constexpr std::uint64_t value() const { return value_; }
    /// True for the zero ID.
    constexpr bool is_zero() const { return value_ == 0; }
    /// Big-endian 6 bytes.
    std::array<std::uint8_t, kSize> to_bytes() const;
    /// Node ID from the first 6 bytes of bytes; nullopt if fewer than 6 are given.
    static std::optional<NodeId> from_bytes(std::span<const std::uint8_t> bytes);
    /// Dotted uppercase hex, e.g. "05.01.01.01.22.00".
    std::string to_string() const;
    /// Parses "05.01.01.01.22.00" or "050101012200" (parse_id); on failure returns nullopt and,
    /// if error is given, a sentence saying what is wrong.
    static std::optional<NodeId> parse(std::string_view text, std::string* error = nullptr);

    /// Ordered by numeric value.
    // The NOLINT: clang-tidy before 18 takes the 0 a defaulted <=> compares its result with for
    // a null pointer constant (llvm/llvm-project#53961); there is no pointer here.
    friend constexpr auto operator<=>(NodeId, NodeId) = default;  // NOLINT(modernize-use-nullptr)

private:
    std::uint64_t value_ = 0;
};

/// A 64-bit OpenLCB event ID.
class EventId {
public:
    /// Number of bytes on the wire.
    static constexpr std::size_t kSize = 8;

    /// The zero event ID.
    constexpr EventId() = default;
    /// Event ID from its numeric value.
    constexpr explicit EventId(std::uint64_t value) : value_(value) {}
    /// Event ID made of a node ID (upper 6 bytes) and a 16-bit suffix, the usual allocation.
    constexpr EventId(NodeId node, std::uint16_t suffix) : value_(node.value() << 16 | suffix) {}

    /// Numeric value.
    constexpr std::uint64_t value() const { return value_; }
    /// Big-endian 8 bytes.
    std::array<std::uint8_t, kSize> to_bytes() const;
    /// Event ID from the first 8 bytes of bytes; nullopt if fewer than 8 are given.
    static std::optional<EventId> from_bytes(std::span<const std::uint8_t> bytes);
    /// Dotted uppercase hex, e.g. "05.01.01.01.22.00.00.01".
    std::string to_string() const;
    /// Parses "05.01.01.01.22.00.00.01" or 16 plain hex digits (parse_id); nullopt plus an
    /// error sentence on failure.
    static std::optional<EventId> parse(std::string_view text, std::string* error = nullptr);

    /// Ordered by numeric value.
    friend constexpr auto operator<=>(EventId, EventId) = default;

private:
    std::uint64_t value_ = 0;
};

/// Event reported by a node that saw its own node ID used by another node (fact sheet 9).
inline constexpr EventId kDuplicateNodeIdEvent{0x0101'0000'0000'0201ull};

/// The one text form of OpenLCB IDs: the `bytes` low-order bytes of value (6 for a node ID, 8 for
/// an event ID), most significant first, each as two uppercase hex digits, joined by dots:
/// format_id(0x050101012200, 6) == "05.01.01.01.22.00".
std::string format_id(std::uint64_t value, std::size_t bytes);

/// The one reader of IDs of `bytes` bytes (1 to 8): `bytes` dot-separated bytes of exactly two
/// hex digits each ("05.01.01.01.22.00"), or 2 * `bytes` hex digits without dots
/// ("050101012200"); either case; no spaces, no "0x". On failure nullopt and, if error is given,
/// a sentence naming `what` (e.g. "node ID") and what is wrong, the faulty byte by its number:
/// "byte 6 of node ID '05.01.01.01.22.0' has 1 hex digit; expected exactly 2".
std::optional<std::uint64_t> parse_id(std::string_view text, std::size_t bytes,
                                      std::string_view what, std::string* error = nullptr);

}  // namespace olcb::base

// The IDs are OpenLCB's own types: every library and program names them olcb::NodeId and
// olcb::EventId.
namespace olcb {
using base::EventId;
using base::kDuplicateNodeIdEvent;
using base::NodeId;
}  // namespace olcb

/// Hash so NodeId can key unordered containers.
template <>
struct std::hash<olcb::base::NodeId> {
    std::size_t operator()(olcb::base::NodeId id) const noexcept {
        return std::hash<std::uint64_t>{}(id.value());
    }
};

/// Hash so EventId can key unordered containers.
template <>
struct std::hash<olcb::base::EventId> {
    std::size_t operator()(olcb::base::EventId id) const noexcept {
        return std::hash<std::uint64_t>{}(id.value());
    }
};
