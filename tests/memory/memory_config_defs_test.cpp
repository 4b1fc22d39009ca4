#include "memory/memory_config_defs.hpp"

#include <gtest/gtest.h>

namespace olcb::memory {
namespace {

TEST(MemoryConfigDefs, ShortFormSpaceFromCommand) {
    EXPECT_EQ(short_form_space(0x41), Space::kConfig);
    EXPECT_EQ(short_form_space(0x42), Space::kAll);
    EXPECT_EQ(short_form_space(0x43), Space::kCdi);
    EXPECT_EQ(short_form_space(0x5B), Space::kCdi);
    EXPECT_FALSE(short_form_space(0x40).has_value());
    EXPECT_FALSE(short_form_space(0x00).has_value());
    // Commands >= 0x80 are not read/write family, so their low bits mean nothing.
    EXPECT_FALSE(short_form_space(0x87).has_value());
}

TEST(MemoryConfigDefs, ShortFormBitsOnlyForHighSpaces) {
    EXPECT_EQ(short_form_bits(Space::kConfig), 1);
    EXPECT_EQ(short_form_bits(Space::kAll), 2);
    EXPECT_EQ(short_form_bits(Space::kCdi), 3);
    EXPECT_EQ(short_form_bits(Space::kAcdiManufacturer), 0);
    EXPECT_EQ(short_form_bits(Space::kAcdiUser), 0);
    EXPECT_EQ(short_form_bits(Space{0x00}), 0);
    EXPECT_TRUE(has_short_form(Space::kConfig));
    EXPECT_FALSE(has_short_form(Space::kAcdiManufacturer));
}

TEST(MemoryConfigDefs, CommandBytesMatchTheFactSheet) {
    EXPECT_EQ(to_u8(Command::kRead) | short_form_bits(Space::kCdi), 0x43);
    EXPECT_EQ(to_u8(Command::kReadReplyFail) | short_form_bits(Space::kCdi), 0x5B);
    EXPECT_EQ(to_u8(Command::kWriteUnderMask) | short_form_bits(Space::kConfig), 0x09);
    EXPECT_EQ(to_u8(Command::kReadStreamReplyFail), 0x78);
    EXPECT_EQ(to_u8(Command::kWriteStreamReplyFail), 0x38);
    EXPECT_EQ(to_u8(Command::kSpaceInfoPresent), 0x87);
    EXPECT_EQ(to_u8(Command::kSpaceInfoNotPresent), 0x86);
    EXPECT_EQ(to_u8(Command::kGetUniqueIdReply), 0x8D);
    EXPECT_EQ(to_u8(Command::kFactoryReset), 0xAA);
    EXPECT_EQ(to_u8(Command::kEnterBootloader), 0xAB);
}

TEST(MemoryConfigDefs, ReplyAndFailClassification) {
    EXPECT_FALSE(is_reply(0x43));
    EXPECT_TRUE(is_reply(0x53));
    EXPECT_TRUE(is_reply(0x5B));
    EXPECT_TRUE(is_reply(0x10));
    EXPECT_TRUE(is_reply(0x82));
    EXPECT_TRUE(is_reply(0x86));
    EXPECT_TRUE(is_reply(0x87));
    EXPECT_TRUE(is_reply(0x8A));
    EXPECT_TRUE(is_reply(0x8D));
    EXPECT_FALSE(is_reply(0x80));
    EXPECT_FALSE(is_reply(0x84));
    EXPECT_FALSE(is_reply(0xA9));

    EXPECT_TRUE(is_fail(0x58));
    EXPECT_TRUE(is_fail(0x1B));
    EXPECT_TRUE(is_fail(0x78));
    EXPECT_FALSE(is_fail(0x08));  // write under mask is a command, not a failure
    EXPECT_FALSE(is_fail(0x53));
    EXPECT_FALSE(is_fail(0x86));

    EXPECT_TRUE(is_stream(0x63));
    EXPECT_FALSE(is_stream(0x43));
    EXPECT_EQ(family_of(0x5B), 0x58);
    EXPECT_EQ(family_of(0x87), 0x87);
}

TEST(MemoryConfigDefs, ReadCountRange) {
    EXPECT_FALSE(is_valid_read_count(0));
    EXPECT_TRUE(is_valid_read_count(1));
    EXPECT_TRUE(is_valid_read_count(64));
    EXPECT_FALSE(is_valid_read_count(65));
}

TEST(MemoryConfigDefs, ErrorCodes) {
    EXPECT_EQ(to_u16(ErrorCode::kSpaceUnknown), 0x1081);
    EXPECT_EQ(to_u16(ErrorCode::kOutOfBounds), 0x1082);
    EXPECT_EQ(to_u16(ErrorCode::kReadOnly), 0x1083);
    EXPECT_EQ(to_u16(ErrorCode::kInvalidArguments), 0x1080);
    EXPECT_TRUE(is_permanent(ErrorCode::kOutOfBounds));
    EXPECT_FALSE(is_temporary(ErrorCode::kOutOfBounds));
    EXPECT_TRUE(is_temporary(ErrorCode::kBufferUnavailable));
    EXPECT_EQ(error_name(ErrorCode::kOutOfBounds), "address out of bounds");
    EXPECT_EQ(error_name(ErrorCode{0x1234}), "");
}

}  // namespace
}  // namespace olcb::memory
