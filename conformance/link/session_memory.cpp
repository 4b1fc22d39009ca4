#include "conformance/link/session_memory.hpp"

#include <algorithm>
#include <utility>

#include "base/error_codes.hpp"

namespace olcb::conform {
namespace {

constexpr std::size_t kChunk = 64;

AccessResult to_access(const MemResult& r) {
    return {r.ok, r.error, r.data, r.not_sent};
}

}  // namespace

AccessResult SessionMemory::read(std::uint8_t space, std::uint32_t address, std::size_t count) {
    // read_range goes on after short replies and stops at the end of the space; what came
    // before the end is the answer, nothing at all is 0x1082.
    MemResult r = session_.read_range(node_, static_cast<memory::Space>(space), address,
                                      static_cast<std::uint32_t>(count), false);
    if (!r.ok) return to_access(r);
    if (r.data.empty() && count != 0)
        return {false, base::to_u16(base::ErrorCode::kOutOfBounds), {}};
    return {true, 0, std::move(r.data)};
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
