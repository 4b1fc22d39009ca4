#include "base/hex.hpp"

#include <algorithm>

namespace olcb::base {

std::string hex_digits(std::uint64_t value, int width, HexCase letters) {
    int digits = 1;
    while (digits < 16 && (value >> (4 * digits)) != 0) ++digits;
    const int size = std::max(width, digits);
    std::string out(static_cast<std::size_t>(size), '0');
    char* at = out.data() + (size - digits);
    for (int i = digits - 1; i >= 0; --i) *at++ = hex_digit(value >> (4 * i), letters);
    return out;
}

std::string hex(std::uint64_t value, int width) {
    std::string out = "0x";
    out.append(hex_digits(value, width));
    return out;
}

std::string hex_bytes(std::span<const std::uint8_t> bytes, std::string_view separator,
                      HexCase letters) {
    std::string out;
    out.reserve(bytes.size() * (2 + separator.size()));
    for (std::size_t i = 0; i < bytes.size(); ++i) {
        if (i != 0) out.append(separator);
        out.push_back(hex_digit(bytes[i] >> 4, letters));
        out.push_back(hex_digit(bytes[i], letters));
    }
    return out;
}

}  // namespace olcb::base
