#include "conformance/link/memory_access.hpp"

namespace olcb::conform {

std::string hex_bytes(std::span<const std::uint8_t> bytes, std::size_t max) {
    constexpr const char* kDigits = "0123456789ABCDEF";
    std::string out;
    for (std::size_t i = 0; i < bytes.size() && i < max; ++i) {
        if (i) out.push_back(' ');
        out.push_back(kDigits[bytes[i] >> 4]);
        out.push_back(kDigits[bytes[i] & 0xF]);
    }
    if (bytes.size() > max) out += " ...";
    return out;
}

}  // namespace olcb::conform
