// The read faults: reads and Get Address Space Information answered against the rules, and the
// rejection codes of unknown and read-only spaces.
#include <gtest/gtest.h>

#include "simnode/faults/fault_test_util.hpp"

namespace olcb::simnode::test {
namespace {

TEST_F(FaultTest, ReadPastEnd) {
    start_with({"read-past-end"});
    const auto end = static_cast<std::uint32_t>(default_cdi().size() + 1);
    const Answer a = exchange(read_cmd(0xFF, end, 16));
    ASSERT_TRUE(a.reply);
    EXPECT_EQ((*a.reply)[1], 0x53);
    EXPECT_EQ(a.reply->size(), 6u + 16u);
}

TEST_F(SimNodeRulesTest, ReadPastEndGarbage) {
    start_with({"read-past-end-garbage"});
    const Answer a = exchange(read_cmd(0xFD, kConfigSize, 8));
    ASSERT_TRUE(a.reply);
    EXPECT_EQ((*a.reply)[1], 0x51) << "Read Reply OK";
    EXPECT_EQ(read(0xFD, kConfigSize, 8), std::vector<std::uint8_t>(8, 0xA5));
    EXPECT_EQ(read(0xFD, kConfigSize + 0x100, 3), std::vector<std::uint8_t>(3, 0xA5));
    EXPECT_EQ(read(0xFD, kConfigSize - 1, 8).size(), 1u) << "a crossing read is still cut";
    EXPECT_EQ(fail_code(exchange(read_cmd(0xFB, kUserSize, 1))), 0x1082) << "0xFD only";
}

TEST_F(FaultTest, SpaceInfoShort) {
    start_with({"space-info-short"});
    EXPECT_EQ(highest(0xFD), 178u - 16u);
    EXPECT_EQ(highest(0xFB), 127u - 16u);
}

TEST_F(SimNodeRulesTest, HighestUnreadable) {
    start_with({"highest-unreadable"});
    EXPECT_EQ(highest(0xFB), kUserSize);
    EXPECT_EQ(highest(0xFD), kConfigSize);
    EXPECT_EQ(fail_code(exchange(read_cmd(0xFB, kUserSize, 1))), 0x1082);
    EXPECT_EQ(fail_code(exchange(read_cmd(0xFD, kConfigSize, 1))), 0x1082);
    EXPECT_EQ(highest(0xFF), default_cdi().size()) << "other spaces as usual";
    EXPECT_EQ(highest(0xFC), 124u);
}

TEST_F(FaultTest, ReplyForm) {
    start_with({"reply-form"});
    Answer a = exchange({0x20, 0x43, 0, 0, 0, 0, 2});  // short form
    ASSERT_TRUE(a.reply);
    EXPECT_EQ(*a.reply, (std::vector<std::uint8_t>{0x20, 0x50, 0, 0, 0, 0, 0xFF, '<', '?'}));
    a = exchange({0x20, 0x40, 0, 0, 0, 15, 0xFD, 1});  // byte-6 form
    ASSERT_TRUE(a.reply);
    EXPECT_EQ(*a.reply, (std::vector<std::uint8_t>{0x20, 0x51, 0, 0, 0, 15, 2}));
}

TEST_F(FaultTest, FieldReadsOnly) {
    start_with({"field-reads-only"});
    EXPECT_EQ(read(0xFC, 0, 64), (std::vector<std::uint8_t>{4})) << "version byte alone";
    EXPECT_EQ(read(0xFC, 1, 64), with_nul("OpenLCB Tools"));
    EXPECT_EQ(read(0xFC, 1, 4), bytes_of("Open")) << "never more than asked";
    EXPECT_EQ(read(0xFC, 42, 64), with_nul("simnode default"));
    EXPECT_EQ(read(0xFC, 83, 64), with_nul("1.0"));
    EXPECT_EQ(read(0xFC, 104, 64), with_nul("0.1.0"));
    EXPECT_EQ(read(0xFC, 2, 64), bytes_of("p")) << "off a field start: one byte";
    EXPECT_EQ(read(0xFC, 124, 64).size(), 1u);
    const Answer end = exchange(read_cmd(0xFC, 125, 8));
    ASSERT_TRUE(end.reply);
    EXPECT_EQ((*end.reply)[1], 0x58) << "at the end still a Read Reply Fail";
    EXPECT_EQ((*end.reply)[7], 0x10);
    EXPECT_EQ((*end.reply)[8], 0x82);

    EXPECT_EQ(read(0xFB, 0, 64), (std::vector<std::uint8_t>{2}));
    EXPECT_EQ(read(0xFB, 1, 64), with_nul("Test node"));
    EXPECT_EQ(read(0xFB, 64, 64), with_nul("Bench"));
    EXPECT_EQ(read(0xFB, 10, 64).size(), 1u);
    const std::vector<std::uint8_t> full(63, 'x');
    write_ok(0xFB, 1, full);
    EXPECT_EQ(read(0xFB, 1, 64), full) << "a field without NUL is returned whole, no more";
    EXPECT_EQ(read(0xFD, 0, 8).size(), 8u) << "other spaces are read as usual";
}

TEST_F(FaultTest, UnknownSpace0x1041) {
    start_with({"unknown-space-0x1041"});
    for (const auto& cmd : {read_cmd(0x10, 0, 4), write_cmd(0x10, 0, {1}), read_cmd(0xFE, 0, 4),
                            write_cmd(0xFE, 0, {1})}) {
        const Answer a = exchange(cmd);
        EXPECT_TRUE(a.rejected);
        EXPECT_EQ(a.code, 0x1041);
        EXPECT_FALSE(a.reply);
    }
    const Answer info = exchange({0x20, 0x84, 0x10});
    ASSERT_TRUE(info.reply) << "Get Address Space Information is unchanged";
    EXPECT_EQ((*info.reply)[1], 0x86);
    EXPECT_EQ(read(0xFD, 15, 1), (std::vector<std::uint8_t>{2}));
}

TEST_F(FaultTest, Readonly0x1041) {
    start_with({"readonly-0x1041"});
    for (const auto& cmd : {write_cmd(0xFF, 0, {'x'}), write_cmd(0xFC, 1, {'x'})}) {
        const Answer a = exchange(cmd);
        EXPECT_TRUE(a.rejected);
        EXPECT_EQ(a.code, 0x1041);
    }
    EXPECT_EQ(read(0xFF, 0, 2), bytes_of("<?"));
    write_ok(0xFD, 15, {3});
    const Answer unknown = exchange(read_cmd(0x10, 0, 4));
    EXPECT_EQ(unknown.code, 0x1081) << "only the read-only code changes";
}

}  // namespace
}  // namespace olcb::simnode::test
