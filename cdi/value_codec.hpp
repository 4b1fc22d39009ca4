// Values of CDI variables, per element: bytes <-> Value <-> text, and the validity rules of the
// CDI standard 5.1.4.2-5.1.4.6 (min/max, map membership, string length, action value).
//
// encode/decode only care whether a value is representable in the element's bytes; check_value
// applies the standard's validity rules. A writer calls check_value first: values that fail it
// "shall not be written". Keeping them apart lets a conformance tool write a deliberately invalid
// value and see how a node reacts.
#pragma once

#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "cdi/codec_result.hpp"
#include "cdi/document.hpp"
#include "cdi/value.hpp"

namespace olcb::cdi {

/// The kind of Value a variable holds; nullopt for <group>, <blob> and unknown elements.
std::optional<ValueKind> value_kind_of(const Element& element);

/// The bytes the variable occupies (8 for <eventid>, 1 for a sizeless <bit>); an error for an
/// element without a value or a size the standard does not allow.
CodecResult<std::uint64_t> value_size(const Element& element);

/// The element's bytes holding `value`, exactly value_size() long. Errors: wrong value kind,
/// value not representable (int out of range, float overflow in strict mode, string too long
/// in strict mode), element without a value. Does not check min/max/map: see check_value.
CodecResult<std::vector<std::uint8_t>> encode(const Element& element, const Value& value,
                                              CodecMode mode = CodecMode::kStrict);

/// The bytes an <action> writes when triggered: its <value> in its size.
CodecResult<std::vector<std::uint8_t>> encode_action(const Element& element);

/// The value stored in `bytes`, which must be value_size() long. Strict mode rejects a string
/// without NUL or with invalid UTF-8; lenient mode returns its bytes as text.
CodecResult<Value> decode(const Element& element, std::span<const std::uint8_t> bytes,
                          CodecMode mode = CodecMode::kStrict);

/// Success when the standard allows writing `value` to `element`: the right kind; int within
/// min (default 0) and max (default the largest of the size); float within min (default 0) and
/// max (default the largest finite of the size), compared after rounding both to the size, NaN
/// never valid; string valid UTF-8 of at most size - 1 bytes without NUL; an <action> only its
/// <value>; and, when a <map> is present, one of its properties (numerically for int and float,
/// exactly for strings, as an event ID for eventid).
CodecStatus check_value(const Element& element, const Value& value);

/// The value written as `text` for this element: decimal integer, decimal float, raw string,
/// dotted event ID (or 16 hex digits). Surrounding spaces are ignored except for strings.
CodecResult<Value> parse_value_text(const Element& element, std::string_view text);

/// Text of `value` that parse_value_text reads back to the same stored bytes: decimal integer,
/// shortest round-trip decimal for the element's float size, raw string, dotted event ID.
std::string format_value(const Element& element, const Value& value);

}  // namespace olcb::cdi
