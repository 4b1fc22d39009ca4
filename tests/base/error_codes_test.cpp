#include "base/error_codes.hpp"

#include <gtest/gtest.h>

#include <set>
#include <string_view>

namespace olcb::base {
namespace {

TEST(ErrorCodes, ValuesAreTheStandardsTable) {
    EXPECT_EQ(to_u16(ErrorCode::kNone), 0x0000);
    EXPECT_EQ(to_u16(ErrorCode::kPermanent), 0x1000);
    EXPECT_EQ(to_u16(ErrorCode::kSourceNotPermitted), 0x1020);
    EXPECT_EQ(to_u16(ErrorCode::kNotFound), 0x1030);
    EXPECT_EQ(to_u16(ErrorCode::kNotImplemented), 0x1040);
    EXPECT_EQ(to_u16(ErrorCode::kSubcommandUnknown), 0x1041);
    EXPECT_EQ(to_u16(ErrorCode::kCommandUnknown), 0x1042);
    EXPECT_EQ(to_u16(ErrorCode::kUnknownMtiOrTransport), 0x1043);
    EXPECT_EQ(to_u16(ErrorCode::kInvalidArguments), 0x1080);
    EXPECT_EQ(to_u16(ErrorCode::kSpaceUnknown), 0x1081);
    EXPECT_EQ(to_u16(ErrorCode::kOutOfBounds), 0x1082);
    EXPECT_EQ(to_u16(ErrorCode::kReadOnly), 0x1083);
    EXPECT_EQ(to_u16(ErrorCode::kTemporary), 0x2000);
    EXPECT_EQ(to_u16(ErrorCode::kTimeout), 0x2010);
    EXPECT_EQ(to_u16(ErrorCode::kTimeoutWaitingForEnd), 0x2011);
    EXPECT_EQ(to_u16(ErrorCode::kBufferUnavailable), 0x2020);
    EXPECT_EQ(to_u16(ErrorCode::kOutOfOrder), 0x2040);
    EXPECT_EQ(to_u16(ErrorCode::kMiddleOrLastWithoutFirst), 0x2041);
    EXPECT_EQ(to_u16(ErrorCode::kFirstBeforePreviousFinished), 0x2042);
    EXPECT_EQ(to_u16(ErrorCode::kTransferError), 0x2080);
    EXPECT_EQ(to_u16(ErrorCode::kAccept), 0x8000);
    EXPECT_EQ(to_u16(ErrorCode::kMiddleOrLastWithoutFirst) & 0xFFF0,
              to_u16(ErrorCode::kOutOfOrder));
}

TEST(ErrorCodes, TypeBitsDecidePermanentOrTemporary) {
    EXPECT_TRUE(is_permanent(ErrorCode::kOutOfBounds));
    EXPECT_FALSE(is_temporary(ErrorCode::kOutOfBounds));
    EXPECT_TRUE(is_permanent(ErrorCode::kPermanent));
    EXPECT_TRUE(is_temporary(ErrorCode::kBufferUnavailable));
    EXPECT_FALSE(is_permanent(ErrorCode::kBufferUnavailable));
    EXPECT_TRUE(is_temporary(ErrorCode::kMiddleOrLastWithoutFirst));
    EXPECT_TRUE(is_temporary(ErrorCode::kFirstBeforePreviousFinished));
    EXPECT_TRUE(is_temporary(std::uint16_t{0x2099}));
    EXPECT_TRUE(is_permanent(std::uint16_t{0x10FF}));
    // Neither: no information, acceptance, and the ill-formed codes with two type bits.
    for (const std::uint16_t code : {0x0000, 0x0042, 0x8000, 0x3000, 0x9000, 0xA000, 0x4000}) {
        EXPECT_FALSE(is_permanent(code)) << std::hex << code;
        EXPECT_FALSE(is_temporary(code)) << std::hex << code;
    }
}

TEST(ErrorCodes, EveryCodeOfTheTableHasItsOwnName) {
    std::set<std::string_view> names;
    unsigned named = 0;
    for (unsigned v = 0; v <= 0xFFFF; ++v) {
        const std::string_view name = error_name(ErrorCode{static_cast<std::uint16_t>(v)});
        if (name.empty()) continue;
        ++named;
        names.insert(name);
    }
    EXPECT_EQ(named, 21u);
    EXPECT_EQ(names.size(), named);
    EXPECT_EQ(error_name(ErrorCode::kOutOfBounds), "address out of bounds");
    EXPECT_EQ(error_name(ErrorCode{0x1234}), "");
}

TEST(ErrorCodes, DescribeFallsBackToTheType) {
    EXPECT_EQ(describe_error(0x1082), "address out of bounds");
    EXPECT_EQ(describe_error(0x2099), "temporary error");
    EXPECT_EQ(describe_error(0x1099), "permanent error");
    EXPECT_EQ(describe_error(0x3000), "unknown error");
    EXPECT_EQ(describe_error(0x0001), "unknown error");
    static_assert(describe_error(0x1081) == "address space unknown");
}

}  // namespace
}  // namespace olcb::base
