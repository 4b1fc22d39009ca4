// SimNode: with faults on, each datagram is decoded once and each reply encoded once (the faults
// change the typed request and reply; see decide()).
#include "simnode/sim_node.hpp"

#include <gtest/gtest.h>

#include "memory/memory_config_codec.hpp"
#include "simnode/sim_node_test_util.hpp"

namespace olcb::simnode {
namespace {

class SimNodeDecodeTest : public test::SimNodeTest {
protected:
    // Runs one exchange and returns how many payloads were decoded and encoded meanwhile.
    memory::CodecCounts counted(const std::vector<std::uint8_t>& request, test::Answer& answer) {
        const memory::CodecCounts before = memory::codec_counts();
        answer = exchange(request);
        const memory::CodecCounts after = memory::codec_counts();
        return {after.decoded - before.decoded, after.encoded - before.encoded};
    }
};

TEST_F(SimNodeDecodeTest, EveryMemoryFaultOnOneDecodeAndOneEncodePerDatagram) {
    start_with({"read-past-end", "space-info-short", "reply-form", "field-reads-only",
                "highest-unreadable", "write-past-end-grows", "readonly-0x1041",
                "unknown-space-0x1041", "lock-rejected", "reset-rejected"});
    test::Answer a;
    memory::CodecCounts n = counted({0x20, 0x41, 0, 0, 0, 0, 8}, a);  // short-form read of 0xFD
    ASSERT_TRUE(a.reply);
    EXPECT_EQ((*a.reply)[1], 0x50) << "reply-form answered in the byte-6 form";
    EXPECT_EQ(n.decoded, 1u);
    EXPECT_EQ(n.encoded, 1u);
    n = counted({0x20, 0x84, 0xFD}, a);  // Space Info, changed by two faults
    ASSERT_TRUE(a.reply);
    EXPECT_EQ(n.decoded, 1u);
    EXPECT_EQ(n.encoded, 1u);
    n = counted({0x20, 0x41, 0xFF, 0xFF, 0xFF, 0x00, 4}, a);  // past the end: filled
    ASSERT_TRUE(a.reply);
    EXPECT_EQ(n.decoded, 1u);
    EXPECT_EQ(n.encoded, 1u);
    n = counted({0x20, 0x88, 2, 1, 0x0D, 0, 0, 1}, a);  // Lock, rejected before the server
    EXPECT_TRUE(a.rejected);
    EXPECT_EQ(n.decoded, 1u);
    EXPECT_EQ(n.encoded, 0u);
}

TEST_F(SimNodeDecodeTest, MaskIgnoredDecodesTheWriteUnderMaskOnce) {
    start_with({"mask-ignored=1"});
    test::Answer a;
    const memory::CodecCounts n = counted({0x20, 0x09, 0, 0, 0, 0, 0x5A, 0x0F}, a);
    EXPECT_TRUE(a.ok);
    EXPECT_EQ(n.decoded, 1u);
}

}  // namespace
}  // namespace olcb::simnode
