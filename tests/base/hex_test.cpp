#include "base/hex.hpp"

#include <gtest/gtest.h>

#include <cstdint>
#include <string>
#include <vector>

namespace olcb::base {
namespace {

TEST(Hex, NumberIsPrefixedAndPadded) {
    EXPECT_EQ(hex(0xA5, 4), "0x00A5");
    EXPECT_EQ(hex(0x1082, 4), "0x1082");
    EXPECT_EQ(hex(0), "0x0");
    EXPECT_EQ(hex(0xFF, 2), "0xFF");
}

TEST(Hex, WiderValueKeepsAllItsDigits) {
    EXPECT_EQ(hex_digits(0x12345, 2), "12345");
    EXPECT_EQ(hex_digits(UINT64_MAX), "FFFFFFFFFFFFFFFF");
    EXPECT_EQ(hex_digits(UINT64_MAX, 18), "00FFFFFFFFFFFFFFFF");
    EXPECT_EQ(hex_digits(0xabc, 0), "ABC");
    EXPECT_EQ(hex_digits(0, 3), "000");
}

TEST(Hex, BytesSeparatedAsAsked) {
    const std::vector<std::uint8_t> bytes{0x0A, 0x0B, 0xFF};
    EXPECT_EQ(hex_bytes(bytes), "0A 0B FF");
    EXPECT_EQ(hex_bytes(bytes, ""), "0A0BFF");
    EXPECT_EQ(hex_bytes(bytes, "."), "0A.0B.FF");
    EXPECT_EQ(hex_bytes({}), "");
}

TEST(Hex, LowercaseOnlyWhenAsked) {
    const std::vector<std::uint8_t> bytes{0x0A, 0xBC, 0xFF};
    EXPECT_EQ(hex_bytes(bytes, "", HexCase::kLower), "0abcff");
    EXPECT_EQ(hex_bytes(bytes, " ", HexCase::kLower), "0a bc ff");
    EXPECT_EQ(hex_digits(0xFD, 2, HexCase::kLower), "fd");
    EXPECT_EQ(hex_digits(0xABC, 4, HexCase::kLower), "0abc");
    EXPECT_EQ(hex_digits(0xABC, 4, HexCase::kUpper), "0ABC");
    EXPECT_EQ(hex_digit(0x1C, HexCase::kLower), 'c');
}

TEST(Hex, PutWritesExactlyTheWidth) {
    char buf[8] = {};
    char* end = put_hex(buf, 0x1ABC, 3);
    EXPECT_EQ(std::string(buf, end), "ABC");
    end = put_hex(buf, 0x5, 4);
    EXPECT_EQ(std::string(buf, end), "0005");
}

TEST(Hex, DigitValuesOfEitherCase) {
    EXPECT_EQ(hex_value('0'), 0);
    EXPECT_EQ(hex_value('9'), 9);
    EXPECT_EQ(hex_value('a'), 10);
    EXPECT_EQ(hex_value('F'), 15);
    EXPECT_EQ(hex_value('g'), -1);
    EXPECT_EQ(hex_value('.'), -1);
    EXPECT_EQ(hex_value('\xFF'), -1);
    EXPECT_EQ(hex_digit(0x1C), 'C');
}

}  // namespace
}  // namespace olcb::base
