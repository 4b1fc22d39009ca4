#include "base/utf8.hpp"

#include <utf8.h>

namespace olcb::base {

namespace {

bool is_continuation(unsigned char c) {
    return (c & 0xC0) == 0x80;
}

// Length of the sequence a lead byte announces; 0 for a byte that cannot start one.
std::size_t sequence_length(unsigned char lead) {
    if (lead < 0x80) return 1;
    if (lead >= 0xC2 && lead <= 0xDF) return 2;
    if (lead >= 0xE0 && lead <= 0xEF) return 3;
    if (lead >= 0xF0 && lead <= 0xF4) return 4;
    return 0;  // continuation byte, overlong lead C0/C1, or beyond U+10FFFF
}

// Appends valid UTF-8 with C0 and C1 controls and DEL as '?' and U+FFFE, U+FFFF as U+FFFD.
void append_valid(std::string& out, std::string_view text) {
    for (std::size_t i = 0; i < text.size(); ++i) {
        const auto c = static_cast<unsigned char>(text[i]);
        const auto next = i + 1 < text.size() ? static_cast<unsigned char>(text[i + 1]) : 0;
        if (c < 0x20 || c == 0x7F) {
            out.push_back('?');
        } else if (c == 0xC2 && next >= 0x80 && next <= 0x9F) {
            out.push_back('?');
            ++i;
        } else if (c == 0xEF && next == 0xBF && i + 2 < text.size() &&
                   (static_cast<unsigned char>(text[i + 2]) & 0xFE) == 0xBE) {
            out += kReplacementCharacter;
            i += 2;
        } else {
            out.push_back(static_cast<char>(c));
        }
    }
}

}  // namespace

std::optional<std::size_t> find_invalid_utf8(std::string_view text) {
    const auto bad = utf8::find_invalid(text.begin(), text.end());
    if (bad == text.end()) return std::nullopt;
    return static_cast<std::size_t>(bad - text.begin());
}

bool is_valid_utf8(std::string_view text) {
    return utf8::is_valid(text.begin(), text.end());
}

bool is_valid_utf8(std::span<const std::uint8_t> bytes) {
    return utf8::is_valid(bytes.begin(), bytes.end());
}

std::string_view truncate_utf8(std::string_view text, std::size_t max_bytes) {
    if (text.size() <= max_bytes) return text;
    // Walk back over at most three continuation bytes to the lead byte of the sequence that
    // text[max_bytes] continues; cut before it only when it announces a sequence running past.
    std::size_t lead = max_bytes;
    std::size_t back = 0;
    while (lead > 0 && back < 3 && is_continuation(static_cast<unsigned char>(text[lead]))) {
        --lead;
        ++back;
    }
    if (back == 0) return text.substr(0, max_bytes);
    const std::size_t len = sequence_length(static_cast<unsigned char>(text[lead]));
    return text.substr(0, len > 1 && lead + len > max_bytes ? lead : max_bytes);
}

std::string printable(std::string_view text) {
    std::string out;
    out.reserve(text.size());
    while (!text.empty()) {
        const std::size_t valid = find_invalid_utf8(text).value_or(text.size());
        append_valid(out, text.substr(0, valid));
        if (valid == text.size()) break;
        out += kReplacementCharacter;
        text.remove_prefix(valid + 1);
    }
    return out;
}

}  // namespace olcb::base
