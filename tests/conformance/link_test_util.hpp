// What the link suites share (link/): the bytes a well-behaved node holds, to compare reads with.
#pragma once

#include <cstdint>
#include <vector>

#include "conformance/sim_bench.hpp"

namespace olcb::conform::testing {

/// The bytes a well-behaved node (simnode, no fault) holds in [address, address+length) of space.
inline std::vector<std::uint8_t> reference_bytes(memory::Space space, std::uint32_t address,
                                                 std::uint32_t length) {
    SimBench good;
    auto node = good.start();
    if (!node) return {};
    return good.session->read_range(*node, space, address, length, false).data;
}

}  // namespace olcb::conform::testing
