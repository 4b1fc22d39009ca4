// The preferred alias generator of CanFrameTransferTN §6 (fact sheet 1.5).
#pragma once

#include <cstdint>

#include "base/node_id.hpp"

namespace olcb {

/// Pseudo-random alias sequence seeded by a node ID; the first alias comes from the un-stepped
/// seed (TN appendix / python-openlcb), so the sequence for 05.01.01.01.22.00 is 343, BD9, ...
class AliasGenerator {
public:
    /// Additive constant of the 48-bit step.
    static constexpr std::uint64_t kIncrement = 0x1B0C'A37A'4BA9ull;

    /// Generator whose state starts at the node ID.
    explicit AliasGenerator(NodeId seed) : state_(seed.value()) {}

    /// Next non-zero alias: first call uses the seed itself, later calls step first.
    std::uint16_t next();
    /// Current 48-bit state (the state the last returned alias was computed from).
    std::uint64_t state() const { return state_; }

    /// One step of the generator: (x * 2^9 + x + c) mod 2^48.
    static constexpr std::uint64_t step(std::uint64_t x) {
        return ((x << 9) + x + kIncrement) & NodeId::kMask;
    }
    /// XOR of the four 12-bit groups of a state (may be 0, which is not a usable alias).
    static constexpr std::uint16_t alias_of(std::uint64_t x) {
        return static_cast<std::uint16_t>((x >> 36 ^ x >> 24 ^ x >> 12 ^ x) & 0xFFF);
    }

private:
    std::uint64_t state_;
    bool started_ = false;
};

}  // namespace olcb
