#include "conformance/link/memory_access.hpp"

#include <algorithm>

#include "base/hex.hpp"

namespace olcb::conform {

std::string hex_bytes(std::span<const std::uint8_t> bytes, std::size_t max) {
    std::string out = base::hex_bytes(bytes.first(std::min(bytes.size(), max)));
    if (bytes.size() > max) out += " ...";
    return out;
}

}  // namespace olcb::conform
