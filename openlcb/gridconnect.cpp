#include "openlcb/gridconnect.hpp"

#include "base/hex.hpp"

namespace olcb::gridconnect {
namespace {

using base::hex_value;

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
    base::put_hex(buf + n, frame.id, digits);
    n += static_cast<std::size_t>(digits);
    buf[n++] = frame.remote ? 'R' : 'N';
    const std::size_t len = frame.len > 8 ? 8 : frame.len;
    for (std::size_t i = 0; i < len; ++i) {
        buf[n++] = base::hex_digit(frame.data[i] >> 4);
        buf[n++] = base::hex_digit(frame.data[i]);
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
