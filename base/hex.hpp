// The one hex formatting: uppercase digits, "0x00A5" for a number, "0A 0B" for bytes; and the one
// reader of a hex digit. Every library formats hex through these, so output never mixes styles.
// Lowercase only where a format outside ours asks for it (OpenLCB_Java's backup files) or where
// text already names things in it (per-space result IDs such as "memory.short-read.fd").
#pragma once

#include <array>
#include <cstdint>
#include <span>
#include <string>
#include <string_view>

namespace olcb::base {

/// The uppercase hex digits, indexed by value.
inline constexpr std::string_view kHexDigits = "0123456789ABCDEF";

/// The lowercase hex digits, indexed by value.
inline constexpr std::string_view kHexDigitsLower = "0123456789abcdef";

/// The letters hex digits are written with.
enum class HexCase : std::uint8_t { kUpper, kLower };

/// The hex digit of the low 4 bits of value, uppercase unless asked.
constexpr char hex_digit(std::uint64_t value, HexCase letters = HexCase::kUpper) {
    return (letters == HexCase::kLower ? kHexDigitsLower : kHexDigits)[value & 0xF];
}

namespace detail {
// -1 for every character that is no hex digit; a table keeps hot parsers branch-light.
constexpr std::array<std::int8_t, 256> make_hex_values() {
    std::array<std::int8_t, 256> table{};
    for (auto& v : table) v = -1;
    for (std::size_t i = 0; i < 10; ++i) table['0' + i] = static_cast<std::int8_t>(i);
    for (std::size_t i = 0; i < 6; ++i) {
        table['A' + i] = static_cast<std::int8_t>(10 + i);
        table['a' + i] = static_cast<std::int8_t>(10 + i);
    }
    return table;
}
inline constexpr std::array<std::int8_t, 256> kHexValues = make_hex_values();
}  // namespace detail

/// The value 0-15 of a hex digit of either case; -1 for any other character.
constexpr int hex_value(char c) {
    return detail::kHexValues[static_cast<unsigned char>(c)];
}

/// Writes exactly `width` uppercase digits, the low ones of value, most significant first, at out
/// and returns the end; for fixed-size buffers on hot paths, where the caller knows value fits.
constexpr char* put_hex(char* out, std::uint64_t value, int width) {
    for (int i = width - 1; i >= 0; --i) *out++ = hex_digit(value >> (4 * i));
    return out;
}

/// Value in hex, zero-padded to at least `width` digits (a wider value keeps all its digits):
/// hex_digits(0xA5, 4) == "00A5", hex_digits(0xFD, 2, HexCase::kLower) == "fd".
std::string hex_digits(std::uint64_t value, int width = 1, HexCase letters = HexCase::kUpper);

/// "0x" and hex_digits(value, width): hex(0xA5, 4) == "0x00A5".
std::string hex(std::uint64_t value, int width = 1);

/// Each byte as two digits with `separator` between them: "0A 0B"; with "" plain "0A0B", with "."
/// the dotted form of node and event IDs; with HexCase::kLower "0a 0b".
std::string hex_bytes(std::span<const std::uint8_t> bytes, std::string_view separator = " ",
                      HexCase letters = HexCase::kUpper);

}  // namespace olcb::base
