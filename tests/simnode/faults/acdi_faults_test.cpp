// acdi-version: the ACDI version bytes of spaces 252 and 251 (docs/faults.md).
#include <gtest/gtest.h>

#include "simnode/faults/fault_test_util.hpp"

namespace olcb::simnode::test {
namespace {

TEST_F(FaultTest, AcdiVersion) {
    start_with({"acdi-version"});
    EXPECT_EQ(read(0xFC, 0, 1), (std::vector<std::uint8_t>{5}));
    EXPECT_EQ(read(0xFB, 0, 1), (std::vector<std::uint8_t>{3}));
}

}  // namespace
}  // namespace olcb::simnode::test
