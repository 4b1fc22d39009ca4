// <string> storage (CDI standard 5.1.4.3): UTF-8 text followed by at least one NUL within the
// element's `size` bytes; the rest is padded with NUL so every byte is written.
#pragma once

#include <cstddef>
#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "cdi/codec_result.hpp"

namespace olcb::cdi {

/// Largest <string> size the codec allocates for; a bigger size attribute is refused, not trusted.
inline constexpr std::uint64_t kMaxStringSize = std::uint64_t{1} << 20;

/// What the bytes of a <string> hold.
struct DecodedString {
    std::string text;         ///< the bytes before the first NUL (all bytes when there is none)
    bool terminated = false;  ///< a NUL was found, as the standard requires
    bool valid_utf8 = false;  ///< text is well-formed UTF-8
};

/// Reads a <string>'s bytes; never fails, the flags tell what is wrong.
DecodedString decode_string(std::span<const std::uint8_t> bytes);

/// The `size` bytes of `text`: the text, a NUL, NUL padding. Errors: size 0 or above
/// kMaxStringSize, a NUL inside the text, and in strict mode a text longer than size - 1 bytes or
/// invalid UTF-8. Lenient mode cuts a long text with base::truncate_utf8 and writes invalid UTF-8
/// as is.
CodecResult<std::vector<std::uint8_t>> encode_string(std::string_view text, std::uint64_t size,
                                                     CodecMode mode = CodecMode::kStrict);

}  // namespace olcb::cdi
