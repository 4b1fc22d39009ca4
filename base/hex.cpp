#include "base/hex.hpp"

#include <algorithm>

namespace olcb::base {

std::string hex_digits(std::uint64_t value, int width) {
    int digits = 1;
    while (digits < 16 && (value >> (4 * digits)) != 0) ++digits;
    const int size = std::max(width, digits);
    std::string out(static_cast<std::size_t>(size), '0');
    put_hex(out.data() + (size - digits), value, digits);
    return out;
}

std::string hex(std::uint64_t value, int width) {
    std::string out = "0x";
    out.append(hex_digits(value, width));
    return out;
}

std::string hex_bytes(std::span<const std::uint8_t> bytes, std::string_view separator) {
    std::string out;
    out.reserve(bytes.size() * (2 + separator.size()));
    for (std::size_t i = 0; i < bytes.size(); ++i) {
        if (i != 0) out.append(separator);
        out.push_back(hex_digit(bytes[i] >> 4));
        out.push_back(hex_digit(bytes[i]));
    }
    return out;
}

}  // namespace olcb::base
