// What the memory access layer prints of bytes: spaced upper-case hex, cut at a maximum.
#include "conformance/link/memory_access.hpp"

#include <gtest/gtest.h>

#include <cstdint>
#include <vector>

namespace olcb::conform {
namespace {

TEST(HexBytes, SpacedUpperCaseAndCutAfterMax) {
    const std::vector<std::uint8_t> bytes = {0x0A, 0xFF, 0x00, 0x7B};
    EXPECT_EQ(hex_bytes(bytes), "0A FF 00 7B");
    EXPECT_EQ(hex_bytes(bytes, 2), "0A FF ...");
    EXPECT_EQ(hex_bytes(std::vector<std::uint8_t>{}), "");
    EXPECT_EQ(hex_bytes(std::vector<std::uint8_t>(16, 0x11)).size(), 16u * 3 - 1);  // no cut
}

}  // namespace
}  // namespace olcb::conform
