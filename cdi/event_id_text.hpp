// <eventid> storage and text (CDI standard 5.1.4.4): 8 bytes big-endian; text is dotted hex,
// "05.01.01.01.22.00.00.01", read and written by the one ID codec (base/node_id.hpp).
#pragma once

#include <array>
#include <cstdint>
#include <span>
#include <string>
#include <string_view>

#include "cdi/codec_result.hpp"
#include "cdi/value.hpp"

namespace olcb::cdi {

/// Bytes of a stored event ID.
inline constexpr std::size_t kEventIdSize = 8;

/// Dotted uppercase hex, 8 groups of 2 digits: "05.01.01.01.22.00.00.01".
std::string format_event_id(EventIdValue id);

/// Parses 8 dotted bytes of exactly 2 hex digits (either case), or 16 hex digits without dots
/// ("0501010122000001"). No spaces, no "0x". Errors name the faulty byte (base::parse_id).
CodecResult<EventIdValue> parse_event_id(std::string_view text);

/// The 8 big-endian bytes of an event ID.
std::array<std::uint8_t, kEventIdSize> encode_event_id(EventIdValue id);

/// The event ID in `bytes`; an error unless there are exactly 8.
CodecResult<EventIdValue> decode_event_id(std::span<const std::uint8_t> bytes);

}  // namespace olcb::cdi
