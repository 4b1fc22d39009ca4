// reply-pending-timeout and reply-pending: the Datagram Received OK's timeout nibble, and a reply
// that takes its time within it, on a node of their own.
#include <gtest/gtest.h>

#include "simnode/sim_node_test_util.hpp"

namespace olcb::simnode::test {
namespace {

class ReplyPendingFaultsTest : public SimNodeTest {};

TEST_F(ReplyPendingFaultsTest, AnOkThatAnnouncesAReplyStatesTwoToTheNSeconds) {
    start_with({"reply-pending-timeout=3"});
    const Answer a = exchange(read_cmd(0xFD, 0, 4));
    ASSERT_TRUE(a.ok);
    EXPECT_EQ(a.ok_flags, 0x83) << "Reply Pending, reply within 2^3 s";
    ASSERT_TRUE(a.reply) << "the reply still comes";
}

TEST_F(ReplyPendingFaultsTest, DefaultsToOneSecondExponent) {
    start_with({"reply-pending-timeout"});
    const Answer a = exchange({0x20, 0x80});  // Get Configuration Options
    ASSERT_TRUE(a.ok);
    EXPECT_EQ(a.ok_flags, 0x81);
}

TEST_F(ReplyPendingFaultsTest, AnOkWithoutReplyPendingStatesNoTimeout) {
    start_with({"reply-pending-timeout=3"});
    const Answer a = exchange({0x20, 0xA8});  // Update Complete: a plain OK
    ASSERT_TRUE(a.ok);
    EXPECT_EQ(a.ok_flags, 0x00);
}

TEST_F(ReplyPendingFaultsTest, ReplyPendingHoldsEveryReplyHalfThePromisedTimeByDefault) {
    start_with({"reply-pending"});
    for (int i = 0; i < 2; ++i) {  // not only the first one
        const Answer a = exchange(read_cmd(0xFD, 0, 4));
        ASSERT_TRUE(a.ok);
        EXPECT_EQ(a.ok_flags, 0x81) << "Reply Pending, reply within 2^1 s";
        ASSERT_TRUE(a.reply) << "the reply comes within the promise";
        EXPECT_GE(a.reply_at - a.ok_at, std::chrono::milliseconds(1000));
        EXPECT_LT(a.reply_at - a.ok_at, std::chrono::milliseconds(1100));
    }
}

TEST_F(ReplyPendingFaultsTest, ReplyPendingTakesTheDelayItIsGiven) {
    start_with({"reply-pending=2:300"});
    const Answer a = exchange({0x20, 0x80});  // Get Configuration Options
    ASSERT_TRUE(a.ok);
    EXPECT_EQ(a.ok_flags, 0x82);
    ASSERT_TRUE(a.reply);
    EXPECT_GE(a.reply_at - a.ok_at, std::chrono::milliseconds(300));
    EXPECT_LT(a.reply_at - a.ok_at, std::chrono::milliseconds(400));
}

TEST_F(ReplyPendingFaultsTest, AWriteAnsweredWithReplyPendingWaitsToo) {
    start_with({"reply-pending=1:500"});
    const Answer a = exchange(write_cmd(0xFD, 0, {1}));
    ASSERT_TRUE(a.ok);
    EXPECT_EQ(a.ok_flags, 0x81);
    ASSERT_TRUE(a.reply);
    EXPECT_GE(a.reply_at - a.ok_at, std::chrono::milliseconds(500));
}

TEST_F(ReplyPendingFaultsTest, WithoutTheFaultNoTimeoutIsStated) {
    start_with({});
    const Answer a = exchange(read_cmd(0xFD, 0, 4));
    ASSERT_TRUE(a.ok);
    EXPECT_EQ(a.ok_flags, 0x80);
}

}  // namespace
}  // namespace olcb::simnode::test
