// The datagram faults: no-datagram-ack (reply before the OK), reply-without-ack (no OK at all)
// and reject-temporary.
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

TEST_F(FaultTest, ReplyWithoutAckNeverSendsAnOkButReplies) {
    start_with({"reply-without-ack"});
    // More datagrams than the node's four buffers: each must be freed although never answered.
    for (std::uint8_t i = 0; i < 8; ++i) {
        const Answer a = exchange(read_cmd(0xFD, i, 1));
        ASSERT_TRUE(a.reply) << "read " << int{i};
        EXPECT_FALSE(a.ok) << "read " << int{i};
        EXPECT_FALSE(a.rejected) << "read " << int{i};
    }
    const Answer w = exchange(write_cmd(0xFD, 15, {7}));
    EXPECT_FALSE(w.ok);
    ASSERT_TRUE(w.reply) << "the Write Reply still comes";
    EXPECT_EQ((*w.reply)[1] & 0xF8, 0x10);
    EXPECT_EQ(read(0xFD, 15, 1), (std::vector<std::uint8_t>{7}));
    const Answer unknown = exchange({0x20, 0xFE});
    EXPECT_TRUE(unknown.rejected) << "a refused request is still answered";
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
