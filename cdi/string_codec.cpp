#include "cdi/string_codec.hpp"

#include <algorithm>

#include "base/utf8.hpp"

namespace olcb::cdi {

DecodedString decode_string(std::span<const std::uint8_t> bytes) {
    DecodedString out;
    const auto nul = std::find(bytes.begin(), bytes.end(), std::uint8_t{0});
    out.terminated = nul != bytes.end();
    out.text.assign(bytes.begin(), nul);
    out.valid_utf8 = base::is_valid_utf8(out.text);
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
        if (const auto bad = base::find_invalid_utf8(text)) {
            return CodecError{"text is not valid UTF-8 (byte " + std::to_string(*bad) + ")"};
        }
        if (text.size() > size - 1) {
            return CodecError{"text of " + std::to_string(text.size()) +
                              " bytes is longer than the " + std::to_string(size - 1) +
                              " bytes a string of size " + std::to_string(size) + " holds"};
        }
    } else {
        text = base::truncate_utf8(text, static_cast<std::size_t>(size - 1));
    }
    std::vector<std::uint8_t> out(static_cast<std::size_t>(size), 0);
    std::copy(text.begin(), text.end(), out.begin());
    return out;
}

}  // namespace olcb::cdi
