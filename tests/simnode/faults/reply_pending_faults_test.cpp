// reply-pending-timeout: the Datagram Received OK's timeout nibble, on a node of its own.
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

TEST_F(ReplyPendingFaultsTest, WithoutTheFaultNoTimeoutIsStated) {
    start_with({});
    const Answer a = exchange(read_cmd(0xFD, 0, 4));
    ASSERT_TRUE(a.ok);
    EXPECT_EQ(a.ok_flags, 0x80);
}

}  // namespace
}  // namespace olcb::simnode::test
