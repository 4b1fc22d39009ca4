#include "conformance/session_memory.hpp"

#include <algorithm>

namespace olcb::conform {
namespace {

constexpr std::size_t kChunk = 64;

AccessResult to_access(const MemResult& r) {
    return {r.ok, r.error, r.data};
}

}  // namespace

AccessResult SessionMemory::read(std::uint8_t space, std::uint32_t address, std::size_t count) {
    AccessResult out{true, 0, {}};
    out.data.reserve(count);
    while (out.data.size() < count) {
        auto n = static_cast<std::uint8_t>(std::min(kChunk, count - out.data.size()));
        auto at = static_cast<std::uint32_t>(address + out.data.size());
        MemResult r = session_.read(node_, static_cast<memory::Space>(space), at, n);
        if (!r.ok) return to_access(r);
        if (r.data.empty()) return {false, 0x1082, std::move(out.data)};
        out.data.insert(out.data.end(), r.data.begin(), r.data.end());
        if (r.data.size() < n) break;  // short read at the end of the space
    }
    return out;
}

AccessResult SessionMemory::write(std::uint8_t space, std::uint32_t address,
                                  std::span<const std::uint8_t> data) {
    for (std::size_t done = 0; done < data.size(); done += kChunk) {
        auto part = data.subspan(done, std::min(kChunk, data.size() - done));
        MemResult r = session_.write(node_, static_cast<memory::Space>(space),
                                     static_cast<std::uint32_t>(address + done), part);
        if (!r.ok) return to_access(r);
    }
    return {true, 0, {}};
}

}  // namespace olcb::conform
