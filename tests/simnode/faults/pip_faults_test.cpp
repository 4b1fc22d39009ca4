// pip-missing-bit: a protocol the node serves is left out of its PIP reply.
#include <gtest/gtest.h>

#include "simnode/faults/fault_test_util.hpp"

namespace olcb::simnode::test {
namespace {

TEST_F(FaultTest, PipMissingCdiBit) {
    start_with({"pip-missing-bit=cdi"});
    take();
    send_addressed(0x828);
    net_.run_for(10ms);
    EXPECT_EQ(take(), std::vector<std::string>{":X19668343N012C745000000000;"});
    EXPECT_TRUE(node_->served_protocols().has(Protocol::kCdi));
}

// The default: the one bit a "shall" ties to the node (CDI 5.1.2, ACDI bit iff <acdi/>).
TEST_F(FaultTest, PipMissingBitDropsTheAcdiBitByDefault) {
    start_with({"pip-missing-bit"});
    take();
    send_addressed(0x828);
    net_.run_for(10ms);
    EXPECT_EQ(take(), std::vector<std::string>{":X19668343N012C741800000000;"});
}

}  // namespace
}  // namespace olcb::simnode::test
