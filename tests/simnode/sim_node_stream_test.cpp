// SimNode's memory-config stream reads, read by a second NodeStack with the stream transport on
// (the way lcc-conform reads), on the simulated bus (its faults: faults/stream_faults_test.cpp).
#include <gtest/gtest.h>

#include <cstdint>
#include <optional>
#include <vector>

#include "openlcb/node_stack.hpp"
#include "simnode/sim_node_test_util.hpp"

namespace olcb::simnode::test {
namespace {

TEST_F(StreamReadTest, CdiByStreamMatchesTheSpaceAndHonoursTheBuffer) {
    boot(default_config());
    EXPECT_TRUE(node_->stack().protocols().has(Protocol::kStream));
    read_cdi(256);
    ASSERT_TRUE(completed_);
    EXPECT_EQ(data_, cdi_bytes());
    EXPECT_EQ(completed_->count, data_.size());
    ASSERT_EQ(outcomes_.size(), 1u);
    EXPECT_EQ(outcomes_[0].flags & 0x80, 0x80);  // Reply Pending
    ASSERT_EQ(replies_.size(), 1u);
    EXPECT_EQ(replies_[0][1], 0x73);  // Read Stream Reply OK, short form
    EXPECT_EQ(replies_[0][7], kDid);
    ASSERT_TRUE(info());
    EXPECT_EQ(info()->buffer, 256);  // node proposes 0xFFFF; ours is smaller
    EXPECT_LE(info()->max_in_window, 256u);
    EXPECT_EQ(info()->proceeds, data_.size() / 256);
}

TEST_F(StreamReadTest, ReadAtTheEndFails1082AndDatagramOnlyNodeRejects1041) {
    boot(default_config());
    const std::uint32_t end = static_cast<std::uint32_t>(cdi_bytes().size());
    const std::vector<std::uint8_t> cmd{0x20,
                                        0x63,
                                        static_cast<std::uint8_t>(end >> 24),
                                        static_cast<std::uint8_t>(end >> 16),
                                        static_cast<std::uint8_t>(end >> 8),
                                        static_cast<std::uint8_t>(end),
                                        0xFF,
                                        kDid,
                                        0,
                                        0,
                                        0,
                                        0};
    auto a = exchange(cmd);
    ASSERT_TRUE(a.reply);
    EXPECT_EQ((*a.reply)[1], 0x7B);
    EXPECT_EQ((*a.reply)[6], 0x10);
    EXPECT_EQ((*a.reply)[7], 0x82);
}

TEST_F(StreamReadTest, StreamsOffIsADatagramOnlyNode) {
    NodeConfig c = default_config();
    c.streams = false;
    boot(std::move(c));
    EXPECT_FALSE(node_->stack().protocols().has(Protocol::kStream));
    auto a = exchange({0x20, 0x63, 0, 0, 0, 0, 0xFF, kDid, 0, 0, 0, 0});
    EXPECT_TRUE(a.rejected);
    EXPECT_EQ(a.code, 0x1041);
    auto options = exchange({0x20, 0x80});
    ASSERT_TRUE(options.reply);
    EXPECT_EQ((*options.reply)[2] & 0x10, 0);  // no "stream reads"
}

}  // namespace
}  // namespace olcb::simnode::test
