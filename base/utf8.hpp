// UTF-8 as the project meets it: text from nodes, files and users that may hold any bytes at all.
#pragma once

#include <cstddef>
#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <string_view>

namespace olcb::base {

/// U+FFFD REPLACEMENT CHARACTER in UTF-8.
inline constexpr std::string_view kReplacementCharacter = "\xEF\xBF\xBD";

/// Offset of the first byte that does not start a well-formed UTF-8 sequence (overlong forms,
/// surrogates, code points above U+10FFFF and cut-off sequences are ill-formed); nullopt when
/// `text` is valid.
std::optional<std::size_t> find_invalid_utf8(std::string_view text);

/// True when `text` is well-formed UTF-8.
bool is_valid_utf8(std::string_view text);

/// True when `bytes` are well-formed UTF-8.
bool is_valid_utf8(std::span<const std::uint8_t> bytes);

/// The longest prefix of `text` of at most `max_bytes` bytes that does not cut a UTF-8 sequence
/// in two: a sequence that would run past `max_bytes` goes whole. Bytes that belong to no
/// sequence (invalid UTF-8) are cut as bytes, so the result is never longer than asked.
std::string_view truncate_utf8(std::string_view text, std::size_t max_bytes);

/// Text that is safe to show on a terminal or to put in a report: each byte that starts no valid
/// sequence becomes U+FFFD (so the count of bad bytes shows), what a terminal acts on (C0 and C1
/// controls, DEL) becomes '?', and the non-characters U+FFFE and U+FFFF (not allowed in XML)
/// become U+FFFD. Valid printable text comes back unchanged.
std::string printable(std::string_view text);

}  // namespace olcb::base
