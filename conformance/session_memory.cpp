#include "conformance/session_memory.hpp"

#include <algorithm>

#include "openlcb/error_codes.hpp"

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
    // Every pass adds at least one byte or returns, so the loop ends after `count` passes.
    while (out.data.size() < count) {
        auto n = static_cast<std::uint8_t>(std::min(kChunk, count - out.data.size()));
        auto at = static_cast<std::uint32_t>(address + out.data.size());
        MemResult r = session_.read(node_, static_cast<memory::Space>(space), at, n);
        const bool end = (r.ok && r.data.empty()) ||
                         (!r.ok && !r.rejected && r.error == error_code::kOutOfBounds);
        if (end) {
            // The end of the space: what came before it is the answer.
            if (!out.data.empty()) return out;
            return {false, error_code::kOutOfBounds, {}};
        }
        if (!r.ok) return to_access(r);
        if (r.data.size() > n) r.data.resize(n);  // never trust the node's length
        // A short reply is not the end: the next read goes on where its data ended.
        out.data.insert(out.data.end(), r.data.begin(), r.data.end());
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
