#include "cdi/int_codec.hpp"

#include "cdi/diagnostic.hpp"

namespace olcb::cdi {

namespace {

using UWide = unsigned __int128;

// 39 digits cover 2^127 - 1; refusing longer text bounds the work and the overflow check.
constexpr std::size_t kMaxDecimalDigits = 39;

}  // namespace

bool is_valid_int_size(std::uint64_t size) {
    return size == 1 || size == 2 || size == 4 || size == 8;
}

WideInt int_lowest(std::uint64_t size, bool is_signed) {
    if (!is_valid_int_size(size) || !is_signed) return 0;
    return -(static_cast<WideInt>(1) << (8 * size - 1));
}

WideInt int_highest(std::uint64_t size, bool is_signed) {
    if (!is_valid_int_size(size)) return 0;
    const unsigned bits = static_cast<unsigned>(8 * size) - (is_signed ? 1 : 0);
    return (static_cast<WideInt>(1) << bits) - 1;
}

CodecResult<std::vector<std::uint8_t>> encode_int(WideInt value, std::uint64_t size,
                                                  bool is_signed) {
    if (!is_valid_int_size(size)) {
        return CodecError{"invalid integer size " + std::to_string(size) +
                          " (valid sizes: 1, 2, 4, 8)"};
    }
    const WideInt lo = int_lowest(size, is_signed);
    const WideInt hi = int_highest(size, is_signed);
    if (value < lo || value > hi) {
        return CodecError{"value " + format_int(value) + " does not fit in " +
                          std::to_string(size) + (is_signed ? " signed" : " unsigned") +
                          " byte(s) (range " + format_int(lo) + " to " + format_int(hi) + ")"};
    }
    // Two's complement falls out of the modular conversion to unsigned.
    UWide bits = static_cast<UWide>(value);
    std::vector<std::uint8_t> out(size);
    for (std::size_t i = size; i-- > 0;) {
        out[i] = static_cast<std::uint8_t>(bits & 0xFF);
        bits >>= 8;
    }
    return out;
}

CodecResult<WideInt> decode_int(std::span<const std::uint8_t> bytes, bool is_signed) {
    if (!is_valid_int_size(bytes.size())) {
        return CodecError{"invalid integer size " + std::to_string(bytes.size()) +
                          " (valid sizes: 1, 2, 4, 8)"};
    }
    std::uint64_t bits = 0;
    for (std::uint8_t b : bytes) bits = (bits << 8) | b;
    WideInt value = bits;
    const unsigned width = static_cast<unsigned>(8 * bytes.size());
    if (is_signed && (bits >> (width - 1)) != 0) value -= static_cast<WideInt>(1) << width;
    return value;
}

std::string format_int(WideInt value) {
    return to_string(value);
}

CodecResult<WideInt> parse_int_text(std::string_view text) {
    std::string_view digits = text;
    bool negative = false;
    if (!digits.empty() && (digits.front() == '-' || digits.front() == '+')) {
        negative = digits.front() == '-';
        digits.remove_prefix(1);
    }
    if (digits.empty()) return CodecError{quoted_excerpt(text) + " is not a decimal integer"};
    for (char c : digits) {
        if (c < '0' || c > '9') {
            return CodecError{quoted_excerpt(text) + " is not a decimal integer"};
        }
    }
    while (digits.size() > 1 && digits.front() == '0') digits.remove_prefix(1);
    if (digits.size() > kMaxDecimalDigits) {
        return CodecError{quoted_excerpt(text) + " is out of the integer range"};
    }
    constexpr UWide kLimit = (UWide{1} << 127) - 1;
    UWide magnitude = 0;
    for (char c : digits) {
        const auto digit = static_cast<unsigned>(c - '0');
        if (magnitude > (kLimit - digit) / 10) {
            return CodecError{quoted_excerpt(text) + " is out of the integer range"};
        }
        magnitude = magnitude * 10 + digit;
    }
    const WideInt value = static_cast<WideInt>(magnitude);
    return negative ? -value : value;
}

}  // namespace olcb::cdi
