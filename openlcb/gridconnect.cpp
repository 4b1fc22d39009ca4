#include "openlcb/gridconnect.hpp"

#include <array>

namespace olcb::gridconnect {
namespace {

constexpr char kHexDigits[] = "0123456789ABCDEF";

// -1 for non-hex characters; a table keeps parsing branch-light on the hot path.
constexpr std::array<std::int8_t, 256> make_hex_table() {
    std::array<std::int8_t, 256> t{};
    for (auto& v : t) v = -1;
    for (int i = 0; i < 10; ++i) t['0' + i] = static_cast<std::int8_t>(i);
    for (int i = 0; i < 6; ++i) {
        t['A' + i] = static_cast<std::int8_t>(10 + i);
        t['a' + i] = static_cast<std::int8_t>(10 + i);
    }
    return t;
}
constexpr auto kHexTable = make_hex_table();

inline int hex_value(char c) {
    return kHexTable[static_cast<unsigned char>(c)];
}

inline bool is_space(char c) {
    return c == ' ' || c == '\t' || c == '\r' || c == '\n';
}

}  // namespace

std::size_t format_into(const CanFrame& frame, char* buf) {
    std::size_t n = 0;
    buf[n++] = ':';
    int digits;
    if (frame.extended) {
        buf[n++] = 'X';
        digits = 8;
    } else {
        buf[n++] = 'S';
        digits = 3;
    }
    for (int i = digits - 1; i >= 0; --i) buf[n++] = kHexDigits[(frame.id >> (4 * i)) & 0xF];
    buf[n++] = frame.remote ? 'R' : 'N';
    const std::size_t len = frame.len > 8 ? 8 : frame.len;
    for (std::size_t i = 0; i < len; ++i) {
        buf[n++] = kHexDigits[frame.data[i] >> 4];
        buf[n++] = kHexDigits[frame.data[i] & 0xF];
    }
    buf[n++] = ';';
    return n;
}

void format_to(const CanFrame& frame, std::string& out) {
    char buf[kMaxFormattedSize];
    out.append(buf, format_into(frame, buf));
}

std::string format(const CanFrame& frame) {
    std::string out;
    format_to(frame, out);
    return out;
}

namespace {

// The kind letter (X extended, S standard) and the hex identifier after it, in range for the
// kind; pos is left on the character after the identifier.
bool parse_header(std::string_view text, std::size_t& pos, CanFrame& frame) {
    const char kind = text[0];
    if (kind == 'X' || kind == 'x') {
        frame.extended = true;
    } else if (kind == 'S' || kind == 's') {
        frame.extended = false;
    } else {
        return false;
    }
    pos = 1;
    std::uint32_t id = 0;
    std::size_t digits = 0;
    while (pos < text.size()) {
        const int v = hex_value(text[pos]);
        if (v < 0) break;
        if (++digits > 8) return false;
        id = (id << 4) | static_cast<std::uint32_t>(v);
        ++pos;
    }
    if (digits == 0 || pos >= text.size()) return false;
    if (id > (frame.extended ? 0x1FFFFFFFu : 0x7FFu)) return false;
    frame.id = id;
    return true;
}

// Up to 8 data bytes as pairs of hex digits.
bool parse_data(std::string_view hex, CanFrame& frame) {
    if (hex.size() % 2 != 0 || hex.size() > 16) return false;
    for (std::size_t i = 0; i < hex.size() / 2; ++i) {
        const int hi = hex_value(hex[2 * i]);
        const int lo = hex_value(hex[2 * i + 1]);
        if (hi < 0 || lo < 0) return false;
        frame.data[i] = static_cast<std::uint8_t>((hi << 4) | lo);
    }
    frame.len = static_cast<std::uint8_t>(hex.size() / 2);
    return true;
}

}  // namespace

std::optional<CanFrame> parse_frame(std::string_view text) {
    while (!text.empty() && is_space(text.front())) text.remove_prefix(1);
    while (!text.empty() && is_space(text.back())) text.remove_suffix(1);
    // Shortest valid text is ":X0N;".
    if (text.size() < 5 || text.front() != ':' || text.back() != ';') return std::nullopt;
    text = text.substr(1, text.size() - 2);

    CanFrame frame;
    std::size_t pos = 0;
    if (!parse_header(text, pos, frame)) return std::nullopt;
    const char type = text[pos++];
    if (type == 'N' || type == 'n') {
        frame.remote = false;
    } else if (type == 'R' || type == 'r') {
        frame.remote = true;
    } else {
        return std::nullopt;
    }
    if (!parse_data(text.substr(pos), frame)) return std::nullopt;
    return frame;
}

}  // namespace olcb::gridconnect
