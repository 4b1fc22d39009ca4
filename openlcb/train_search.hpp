// Train Search (TrainSearchS §5, §6): the event IDs 09.00.99.FF.qq.qq.qq.rr a throttle sends in
// Identify Producer to find train nodes or have a command station create one, their flag byte,
// and the matching algorithm (§6.3) a train node applies to them.
#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>

#include "base/node_id.hpp"

namespace olcb::train_search {

/// The range's fixed top four bytes (§5.1); the low four carry the query and the flags.
inline constexpr std::uint64_t kPrefix = 0x0900'99FF'0000'0000ull;
inline constexpr std::uint64_t kPrefixMask = 0xFFFF'FFFF'0000'0000ull;

/// Flag byte bits (§5.2, table 3).
namespace flags {
inline constexpr std::uint8_t kAllocate = 0x80;     ///< create a train node if none answers
inline constexpr std::uint8_t kExact = 0x40;        ///< exact matches only
inline constexpr std::uint8_t kAddressOnly = 0x20;  ///< match the address, not the name
inline constexpr std::uint8_t kProtocolMask = 0x1F;
}  // namespace flags

/// Track protocol field values (flag bits 4-0, table 4) a sender uses.
namespace protocol {
inline constexpr std::uint8_t kAny = 0x00;
inline constexpr std::uint8_t kNative = 0x01;           ///< native OpenLCB train node
inline constexpr std::uint8_t kMfx = 0x02;              ///< MFX / M4
inline constexpr std::uint8_t kMarklinMotorola = 0x04;  ///< bits 1-0: the MM version
inline constexpr std::uint8_t kDcc = 0x08;              ///< bits 1-0: speed steps
inline constexpr std::uint8_t kDccLongAddress = 0x04;   ///< with kDcc: force a 14-bit address
}  // namespace protocol

/// The empty nibble: pads a short query and separates terms.
inline constexpr std::uint8_t kEmptyNibble = 0xF;

/// What kind of train a node is, for the matching algorithm.
enum class TrackProtocol : std::uint8_t {
    kNative,           ///< an OpenLCB train node (its address is user-assigned, any value)
    kDcc,              ///< DCC; short (7-bit) or long (14-bit) address
    kMarklinMotorola,  ///< Märklin-Motorola
    kMfx,              ///< MFX / M4
};

/// A train's identifying properties (§6): name (digits matter), protocol and address.
struct TrainIdentity {
    std::string name;
    TrackProtocol protocol = TrackProtocol::kDcc;
    std::uint32_t address = 0;
    bool long_address = false;  ///< DCC only: a 14-bit address
};

/// One search: the six query nibbles (MSB first) and the flag byte.
struct Query {
    std::array<std::uint8_t, 6> nibbles{};
    std::uint8_t flags = 0;

    /// Nibbles 0x0-0x9 and 0xF as given by text ("12", "4 12" separated), padded with 0xF:
    /// nullopt when text holds anything else or more than six positions.
    static std::optional<Query> of(std::string_view text, std::uint8_t flag_byte);
    /// The query an event ID of the range carries; nullopt outside the range.
    static std::optional<Query> from_event(EventId id);
    /// The event ID of the range that carries this query.
    EventId event() const;
    /// True when a nibble (0xA-0xE) or the protocol field holds a value the standard reserves
    /// ("check upon receipt": such a query matches nothing, §6.3).
    bool has_reserved() const;
    /// "12 exact address-only allocate DCC": for messages.
    std::string to_string() const;
};

/// True when id lies in the Train Search range (§5.1).
constexpr bool in_range(EventId id) {
    return (id.value() & kPrefixMask) == kPrefix;
}

/// §6.3: whether a train with these properties matches the query (reserved values match
/// nothing).
bool matches(const Query& query, const TrainIdentity& train);

/// The track protocol a query's flag byte asks for; nullopt for "any" (and reserved values).
std::optional<TrackProtocol> requested_protocol(std::uint8_t flag_byte);

/// True when the flag byte asks for a DCC long address (§6.3).
bool requests_long_address(std::uint8_t flag_byte);

}  // namespace olcb::train_search
