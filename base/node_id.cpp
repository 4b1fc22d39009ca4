#include "base/node_id.hpp"

#include <algorithm>

#include "base/hex.hpp"
#include "base/utf8.hpp"

namespace olcb::base {
namespace {

// Longer text cannot be an ID; refusing it early keeps messages short.
constexpr std::size_t kMaxTextLength = 64;
// The bytes of the examples messages give: "05.01.01.01.22.00" for a node ID, ".00.01" more for
// an event ID.
constexpr std::array<std::uint8_t, 8> kExample = {0x05, 0x01, 0x01, 0x01, 0x22, 0x00, 0x00, 0x01};

// Appending (rather than operator+ chains) keeps g++ 12's -Wrestrict false positive away.
template <class... Parts>
std::string concat(const Parts&... parts) {
    std::string out;
    (out.append(parts), ...);
    return out;
}

std::string example(std::size_t bytes) {
    return hex_bytes(std::span(kExample).first(bytes), ".");
}

// "node ID '05.01'", the text made safe for a terminal.
std::string named(std::string_view what, std::string_view text) {
    return concat(what, std::string_view(" '"), printable(text), std::string_view("'"));
}

// The character as typed, or \xNN where a terminal would not show it as itself.
std::string shown(char c) {
    const auto u = static_cast<unsigned char>(c);
    if (u < 0x21 || u > 0x7E) return concat(std::string_view("\\x"), hex_digits(u, 2));
    return std::string(1, c);
}

// nullopt, with the reason when the caller asked for one.
std::optional<std::uint64_t> fail(std::string* error, std::string reason) {
    if (error) *error = std::move(reason);
    return std::nullopt;
}

std::string digits_text(std::size_t n) {
    return concat(std::to_string(n), std::string_view(n == 1 ? " hex digit" : " hex digits"));
}

// The value of `digits`; the first one that is no hex digit is named with the whole text.
std::optional<std::uint64_t> hex_run(std::string_view digits, std::string_view text,
                                     std::string_view what, std::string* error) {
    std::uint64_t value = 0;
    for (const char c : digits) {
        const int v = hex_value(c);
        if (v < 0) {
            return fail(error, concat(named(what, text), std::string_view(": '"), shown(c),
                                      std::string_view("' is not a hex digit")));
        }
        value = value << 4 | static_cast<std::uint64_t>(v);
    }
    return value;
}

// 2 * bytes hex digits without dots.
std::optional<std::uint64_t> parse_plain(std::string_view text, std::size_t bytes,
                                         std::string_view what, std::string* error) {
    const auto value = hex_run(text, text, what, error);
    if (!value) return std::nullopt;
    if (text.size() != 2 * bytes) {
        return fail(error,
                    concat(named(what, text), std::string_view(" has "), digits_text(text.size()),
                           std::string_view("; expected "), digits_text(2 * bytes),
                           std::string_view(", or "), std::to_string(bytes),
                           std::string_view(" dotted bytes like "), example(bytes)));
    }
    return value;
}

// One dotted byte, number `index` (from 1): exactly two hex digits.
std::optional<std::uint64_t> parse_byte(std::string_view part, std::size_t index,
                                        std::string_view text, std::string_view what,
                                        std::string* error) {
    const std::string label = concat(std::string_view("byte "), std::to_string(index),
                                     std::string_view(" of "), named(what, text));
    if (part.empty()) return fail(error, concat(label, std::string_view(" is empty")));
    const auto value = hex_run(part, text, what, error);
    if (!value) return std::nullopt;
    if (part.size() != 2) {
        return fail(error, concat(label, std::string_view(" has "), digits_text(part.size()),
                                  std::string_view("; expected exactly 2")));
    }
    return value;
}

// `bytes` dot-separated bytes.
std::optional<std::uint64_t> parse_dotted(std::string_view text, std::size_t bytes,
                                          std::string_view what, std::string* error) {
    const auto groups = static_cast<std::size_t>(std::count(text.begin(), text.end(), '.')) + 1;
    if (groups != bytes) {
        return fail(error,
                    concat(named(what, text), std::string_view(" has "), std::to_string(groups),
                           std::string_view(" groups; expected "), std::to_string(bytes),
                           std::string_view(" like "), example(bytes)));
    }
    std::uint64_t value = 0;
    std::size_t start = 0;
    for (std::size_t i = 1; i <= bytes; ++i) {
        const std::size_t end = std::min(text.find('.', start), text.size());
        const auto byte = parse_byte(text.substr(start, end - start), i, text, what, error);
        if (!byte) return std::nullopt;
        value = value << 8 | *byte;
        start = end + 1;
    }
    return value;
}

template <std::size_t N>
std::array<std::uint8_t, N> to_big_endian(std::uint64_t value) {
    std::array<std::uint8_t, N> out{};
    for (std::size_t i = 0; i < N; ++i) {
        out[i] = static_cast<std::uint8_t>(value >> (8 * (N - 1 - i)));
    }
    return out;
}

std::optional<std::uint64_t> from_big_endian(std::span<const std::uint8_t> bytes, std::size_t n) {
    if (bytes.size() < n) return std::nullopt;
    std::uint64_t value = 0;
    for (std::size_t i = 0; i < n; ++i) value = value << 8 | bytes[i];
    return value;
}

}  // namespace

std::string format_id(std::uint64_t value, std::size_t bytes) {
    const auto all = to_big_endian<8>(value);
    return hex_bytes(std::span(all).last(std::clamp<std::size_t>(bytes, 1, all.size())), ".");
}

std::optional<std::uint64_t> parse_id(std::string_view text, std::size_t bytes,
                                      std::string_view what, std::string* error) {
    bytes = std::clamp<std::size_t>(bytes, 1, kExample.size());
    if (text.empty()) return fail(error, concat(std::string_view("empty "), what));
    if (text.size() > kMaxTextLength) {
        return fail(
            error, concat(what, std::string_view(" text too long ("), std::to_string(text.size()),
                          std::string_view(" characters; expected "), std::to_string(3 * bytes - 1),
                          std::string_view(" like "), example(bytes), std::string_view(")")));
    }
    if (text.find('.') == std::string_view::npos) return parse_plain(text, bytes, what, error);
    return parse_dotted(text, bytes, what, error);
}

std::array<std::uint8_t, NodeId::kSize> NodeId::to_bytes() const {
    return to_big_endian<kSize>(value_);
}

std::optional<NodeId> NodeId::from_bytes(std::span<const std::uint8_t> bytes) {
    if (auto v = from_big_endian(bytes, kSize)) return NodeId(*v);
    return std::nullopt;
}

std::string NodeId::to_string() const {
    return format_id(value_, kSize);
}

std::optional<NodeId> NodeId::parse(std::string_view text, std::string* error) {
    if (auto v = parse_id(text, kSize, "node ID", error)) return NodeId(*v);
    return std::nullopt;
}

std::array<std::uint8_t, EventId::kSize> EventId::to_bytes() const {
    return to_big_endian<kSize>(value_);
}

std::optional<EventId> EventId::from_bytes(std::span<const std::uint8_t> bytes) {
    if (auto v = from_big_endian(bytes, kSize)) return EventId(*v);
    return std::nullopt;
}

std::string EventId::to_string() const {
    return format_id(value_, kSize);
}

std::optional<EventId> EventId::parse(std::string_view text, std::string* error) {
    if (auto v = parse_id(text, kSize, "event ID", error)) return EventId(*v);
    return std::nullopt;
}

}  // namespace olcb::base
