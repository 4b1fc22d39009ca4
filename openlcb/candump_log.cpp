#include "openlcb/candump_log.hpp"

#include <cstdio>

#include "base/hex.hpp"

namespace olcb::candump {

namespace {

using base::hex_digit;
using base::hex_value;

// Parses an unsigned decimal of at most `max_digits` digits; the whole view must be digits.
std::optional<std::uint64_t> parse_decimal(std::string_view s, std::size_t max_digits) {
    if (s.empty() || s.size() > max_digits) return std::nullopt;
    std::uint64_t v = 0;
    for (char c : s) {
        if (c < '0' || c > '9') return std::nullopt;
        v = v * 10 + static_cast<std::uint64_t>(c - '0');
    }
    return v;
}

// "(seconds.micros) " at the start of line, which it then drops.
std::optional<std::chrono::microseconds> take_timestamp(std::string_view& line) {
    if (line.size() < 3 || line.front() != '(') return std::nullopt;
    const auto close = line.find(')');
    if (close == std::string_view::npos) return std::nullopt;
    const std::string_view stamp = line.substr(1, close - 1);
    const auto dot = stamp.find('.');
    if (dot == std::string_view::npos) return std::nullopt;
    const auto seconds = parse_decimal(stamp.substr(0, dot), 12);
    const auto micros = parse_decimal(stamp.substr(dot + 1), 6);
    if (!seconds || !micros || stamp.size() - dot - 1 != 6) return std::nullopt;
    line.remove_prefix(close + 1);
    if (line.empty() || line.front() != ' ') return std::nullopt;
    line.remove_prefix(1);
    return std::chrono::microseconds(*seconds * 1'000'000 + *micros);
}

// Data bytes, optionally separated by '.' as canplayer accepts.
bool parse_data(std::string_view rest, CanFrame& frame) {
    std::size_t i = 0;
    while (i < rest.size()) {
        if (rest[i] == '.') {
            ++i;
            continue;
        }
        if (frame.len == 8 || i + 1 >= rest.size()) return false;
        const int hi = hex_value(rest[i]);
        const int lo = hex_value(rest[i + 1]);
        if (hi < 0 || lo < 0) return false;
        frame.data[frame.len++] = static_cast<std::uint8_t>(hi << 4 | lo);
        i += 2;
    }
    return true;
}

// "ID#DATA" | "ID#R[len]"
bool parse_frame(std::string_view text, CanFrame& frame) {
    const auto hash = text.find('#');
    if (hash != 3 && hash != 8) return false;
    std::uint32_t id = 0;
    for (std::size_t i = 0; i < hash; ++i) {
        const int v = hex_value(text[i]);
        if (v < 0) return false;
        id = id << 4 | static_cast<std::uint32_t>(v);
    }
    frame.extended = hash == 8;
    if (id > (frame.extended ? 0x1FFFFFFFu : 0x7FFu)) return false;  // error frame or junk
    frame.id = id;
    const std::string_view rest = text.substr(hash + 1);
    if (rest.empty() || (rest.front() != 'R' && rest.front() != 'r'))
        return parse_data(rest, frame);
    frame.remote = true;
    if (rest.size() == 1) return true;
    if (rest.size() != 2 || rest[1] < '0' || rest[1] > '8') return false;
    frame.len = static_cast<std::uint8_t>(rest[1] - '0');
    return true;
}

}  // namespace

std::string format(const CanFrame& frame, std::chrono::microseconds timestamp,
                   std::string_view interface) {
    const long long us = timestamp.count() < 0 ? 0 : timestamp.count();
    char head[40];
    std::snprintf(head, sizeof head, "(%010lld.%06lld) ", us / 1'000'000, us % 1'000'000);
    std::string out = head;
    out.append(interface);
    out.push_back(' ');
    const int digits = frame.extended ? 8 : 3;
    const std::uint32_t id = frame.id & (frame.extended ? 0x1FFFFFFFu : 0x7FFu);
    out.append(base::hex_digits(id, digits));
    out.push_back('#');
    const std::uint8_t len = frame.len > 8 ? 8 : frame.len;
    if (frame.remote) {
        out.push_back('R');
        if (len != 0) out.push_back(static_cast<char>('0' + len));
        return out;
    }
    for (std::uint8_t i = 0; i < len; ++i) {
        out.push_back(hex_digit(frame.data[i] >> 4));
        out.push_back(hex_digit(frame.data[i]));
    }
    return out;
}

std::optional<Entry> parse(std::string_view line) {
    while (!line.empty() && (line.back() == '\n' || line.back() == '\r' || line.back() == ' ' ||
                             line.back() == '\t')) {
        line.remove_suffix(1);
    }
    Entry entry;
    const auto stamp = take_timestamp(line);
    if (!stamp) return std::nullopt;
    entry.timestamp = *stamp;
    // "iface "
    const auto space = line.find(' ');
    if (space == 0 || space == std::string_view::npos || space > kMaxInterfaceName) {
        return std::nullopt;
    }
    entry.interface = std::string(line.substr(0, space));
    line.remove_prefix(space + 1);
    if (!parse_frame(line, entry.frame)) return std::nullopt;
    return entry;
}

}  // namespace olcb::candump
