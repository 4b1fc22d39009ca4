#include "cdi/string_codec.hpp"

#include <algorithm>

namespace olcb::cdi {

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

}  // namespace

std::optional<std::size_t> find_invalid_utf8(std::string_view text) {
    std::size_t i = 0;
    while (i < text.size()) {
        const auto lead = static_cast<unsigned char>(text[i]);
        const std::size_t len = sequence_length(lead);
        if (len == 0 || i + len > text.size()) return i;
        for (std::size_t k = 1; k < len; ++k) {
            if (!is_continuation(static_cast<unsigned char>(text[i + k]))) return i;
        }
        if (len >= 3) {
            // The second byte's range rules out overlong forms, surrogates and > U+10FFFF.
            const auto second = static_cast<unsigned char>(text[i + 1]);
            if ((lead == 0xE0 && second < 0xA0) || (lead == 0xED && second > 0x9F) ||
                (lead == 0xF0 && second < 0x90) || (lead == 0xF4 && second > 0x8F)) {
                return i;
            }
        }
        i += len;
    }
    return std::nullopt;
}

bool is_valid_utf8(std::string_view text) {
    return !find_invalid_utf8(text).has_value();
}

std::string_view truncate_utf8(std::string_view text, std::size_t max_bytes) {
    if (text.size() <= max_bytes) return text;
    // Walk back over at most three continuation bytes to the sequence's lead byte.
    std::size_t cut = max_bytes;
    std::size_t back = 0;
    while (cut > 0 && back < 3 && is_continuation(static_cast<unsigned char>(text[cut]))) {
        --cut;
        ++back;
    }
    if (back > 0) {
        // Only a stray extra continuation byte at max_bytes lets the sequence at text[cut] end
        // by max_bytes; then that whole sequence is kept.
        const std::size_t len = sequence_length(static_cast<unsigned char>(text[cut]));
        if (len != 0 && cut + len <= max_bytes) cut = max_bytes;
    }
    return text.substr(0, cut);
}

DecodedString decode_string(std::span<const std::uint8_t> bytes) {
    DecodedString out;
    const auto nul = std::find(bytes.begin(), bytes.end(), std::uint8_t{0});
    out.terminated = nul != bytes.end();
    out.text.assign(bytes.begin(), nul);
    out.valid_utf8 = is_valid_utf8(out.text);
    return out;
}

CodecResult<std::vector<std::uint8_t>> encode_string(std::string_view text, std::uint64_t size,
                                                     CodecMode mode) {
    if (size == 0) return CodecError{"a string of size 0 has no room for its NUL terminator"};
    if (size > kMaxStringSize) {
        return CodecError{"string size " + std::to_string(size) + " exceeds the supported " +
                          std::to_string(kMaxStringSize) + " bytes"};
    }
    if (const auto nul = text.find('\0'); nul != std::string_view::npos) {
        return CodecError{"text contains a NUL byte at offset " + std::to_string(nul)};
    }
    if (mode == CodecMode::kStrict) {
        if (const auto bad = find_invalid_utf8(text)) {
            return CodecError{"text is not valid UTF-8 (byte " + std::to_string(*bad) + ")"};
        }
        if (text.size() > size - 1) {
            return CodecError{"text of " + std::to_string(text.size()) +
                              " bytes is longer than the " + std::to_string(size - 1) +
                              " bytes a string of size " + std::to_string(size) + " holds"};
        }
    } else {
        text = truncate_utf8(text, static_cast<std::size_t>(size - 1));
    }
    std::vector<std::uint8_t> out(static_cast<std::size_t>(size), 0);
    std::copy(text.begin(), text.end(), out.begin());
    return out;
}

}  // namespace olcb::cdi
