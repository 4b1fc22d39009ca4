// The datagram faults: no-datagram-ack (reply before the OK) and reject-temporary.
#include <gtest/gtest.h>

#include "simnode/faults/fault_test_util.hpp"

namespace olcb::simnode::test {
namespace {

TEST_F(FaultTest, NoDatagramAck) {
    start_with({"no-datagram-ack"});
    const Answer a = exchange(read_cmd(0xFD, 15, 1));
    ASSERT_TRUE(a.reply);
    ASSERT_TRUE(a.ok);
    EXPECT_LT(a.reply_index, a.ok_index) << "reply datagram came before the Datagram OK";
}

TEST_F(FaultTest, RejectTemporaryThenWorks) {
    start_with({"reject-temporary=3"});
    for (int i = 0; i < 3; ++i) {
        const Answer a = exchange(read_cmd(0xFD, 15, 1));
        EXPECT_TRUE(a.rejected);
        EXPECT_EQ(a.code, 0x2020);
    }
    EXPECT_EQ(read(0xFD, 15, 1), (std::vector<std::uint8_t>{2}));
    EXPECT_EQ(node_->counters().temporary_rejects, 3u);
}

}  // namespace
}  // namespace olcb::simnode::test
