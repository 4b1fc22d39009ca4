// Unsigned numbers as people type them on a command line or in a JSON string.
#pragma once

#include <charconv>
#include <cstdint>
#include <optional>
#include <string_view>

namespace olcb::base {

/// The whole text as an unsigned number: decimal, or hexadecimal after "0x"/"0X"; nullopt for
/// anything else (empty, a sign, trailing characters, out of range).
inline std::optional<std::uint64_t> parse_unsigned(std::string_view text) {
    int radix = 10;
    if (text.starts_with("0x") || text.starts_with("0X")) {
        text.remove_prefix(2);
        radix = 16;
    }
    std::uint64_t value = 0;
    const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), value, radix);
    if (text.empty() || ec != std::errc() || end != text.data() + text.size()) return std::nullopt;
    return value;
}

}  // namespace olcb::base
