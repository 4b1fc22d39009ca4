#include "cdi/event_id_text.hpp"

#include <algorithm>

namespace olcb::cdi {

namespace {

// Longer text cannot be an event ID; refusing it early keeps messages short.
constexpr std::size_t kMaxTextLength = 64;
constexpr std::size_t kGroups = 8;

int hex_digit(char c) {
    if (c >= '0' && c <= '9') return c - '0';
    if (c >= 'a' && c <= 'f') return c - 'a' + 10;
    if (c >= 'A' && c <= 'F') return c - 'A' + 10;
    return -1;
}

std::string quoted(std::string_view text) {
    return "'" + std::string(text) + "'";
}

std::string bad_digit(std::string_view text, char c) {
    static constexpr char kHex[] = "0123456789ABCDEF";
    const auto u = static_cast<unsigned char>(c);
    std::string shown(1, c);
    if (u < 0x21 || u > 0x7E) shown = std::string("\\x") + kHex[u >> 4] + kHex[u & 0xF];
    return "event ID " + quoted(text) + ": '" + shown + "' is not a hex digit";
}

// 16 hex digits without dots.
CodecResult<EventIdValue> parse_plain_hex(std::string_view text) {
    for (char c : text) {
        if (hex_digit(c) < 0) return CodecError{bad_digit(text, c)};
    }
    if (text.size() != 2 * kGroups) {
        return CodecError{"event ID " + quoted(text) + " has " + std::to_string(text.size()) +
                          " hex digits; expected 16, or 8 dotted groups like " +
                          "05.01.01.01.22.00.00.01"};
    }
    EventIdValue id = 0;
    for (char c : text) id = (id << 4) | static_cast<EventIdValue>(hex_digit(c));
    return id;
}

// 8 dotted groups of 2 hex digits.
CodecResult<EventIdValue> parse_dotted(std::string_view text) {
    std::size_t groups = 1;
    for (char c : text) groups += c == '.' ? 1 : 0;
    if (groups != kGroups) {
        return CodecError{"event ID " + quoted(text) + " has " + std::to_string(groups) +
                          " groups; expected 8 like 05.01.01.01.22.00.00.01"};
    }
    EventIdValue id = 0;
    std::size_t start = 0;
    for (std::size_t g = 0; g < kGroups; ++g) {
        const std::size_t end = std::min(text.find('.', start), text.size());
        const std::string_view group = text.substr(start, end - start);
        const std::string label = "group " + std::to_string(g + 1) + " of event ID " + quoted(text);
        if (group.empty()) return CodecError{"empty " + label};
        for (char c : group) {
            if (hex_digit(c) < 0) return CodecError{bad_digit(text, c)};
        }
        if (group.size() != 2) {
            return CodecError{label + " has " + std::to_string(group.size()) +
                              " hex digits; expected exactly 2"};
        }
        id = (id << 8) | static_cast<EventIdValue>(hex_digit(group[0]) << 4 | hex_digit(group[1]));
        start = end + 1;
    }
    return id;
}

}  // namespace

std::string format_event_id(EventIdValue id) {
    static constexpr char kHex[] = "0123456789ABCDEF";
    std::string out;
    out.reserve(3 * kGroups - 1);
    for (int shift = 56; shift >= 0; shift -= 8) {
        const auto byte = static_cast<unsigned>((id >> shift) & 0xFF);
        if (shift != 56) out += '.';
        out += kHex[byte >> 4];
        out += kHex[byte & 0xF];
    }
    return out;
}

CodecResult<EventIdValue> parse_event_id(std::string_view text) {
    if (text.empty()) return CodecError{"empty event ID"};
    if (text.size() > kMaxTextLength) {
        return CodecError{"event ID text too long (" + std::to_string(text.size()) +
                          " characters; expected 23 like 05.01.01.01.22.00.00.01)"};
    }
    if (text.find('.') == std::string_view::npos) return parse_plain_hex(text);
    return parse_dotted(text);
}

std::array<std::uint8_t, kEventIdSize> encode_event_id(EventIdValue id) {
    std::array<std::uint8_t, kEventIdSize> out{};
    for (std::size_t i = kEventIdSize; i-- > 0;) {
        out[i] = static_cast<std::uint8_t>(id & 0xFF);
        id >>= 8;
    }
    return out;
}

CodecResult<EventIdValue> decode_event_id(std::span<const std::uint8_t> bytes) {
    if (bytes.size() != kEventIdSize) {
        return CodecError{"an event ID has 8 bytes, not " + std::to_string(bytes.size())};
    }
    EventIdValue id = 0;
    for (std::uint8_t b : bytes) id = (id << 8) | b;
    return id;
}

}  // namespace olcb::cdi
