#include "cdi/int_codec.hpp"

#include <gtest/gtest.h>

#include <vector>

namespace olcb::cdi {
namespace {

using Bytes = std::vector<std::uint8_t>;

constexpr WideInt kTwo64 = static_cast<WideInt>(1) << 64;
constexpr WideInt kTwo63 = static_cast<WideInt>(1) << 63;

Bytes encoded(WideInt value, std::uint64_t size, bool is_signed) {
    auto r = encode_int(value, size, is_signed);
    EXPECT_TRUE(r.ok()) << r.error().message;
    return r.ok() ? r.value() : Bytes{};
}

WideInt decoded(const Bytes& bytes, bool is_signed) {
    auto r = decode_int(bytes, is_signed);
    EXPECT_TRUE(r.ok()) << r.error().message;
    return r.ok() ? r.value() : 0;
}

struct Limits {
    std::uint64_t size;
    bool is_signed;
    WideInt lowest;
    WideInt highest;
    Bytes lowest_bytes;
    Bytes highest_bytes;
};

class IntLimitsTest : public ::testing::TestWithParam<Limits> {};

TEST_P(IntLimitsTest, LimitsEncodeToExpectedBytesAndBack) {
    const Limits& p = GetParam();
    EXPECT_EQ(int_lowest(p.size, p.is_signed), p.lowest);
    EXPECT_EQ(int_highest(p.size, p.is_signed), p.highest);
    EXPECT_EQ(encoded(p.lowest, p.size, p.is_signed), p.lowest_bytes);
    EXPECT_EQ(encoded(p.highest, p.size, p.is_signed), p.highest_bytes);
    EXPECT_EQ(decoded(p.lowest_bytes, p.is_signed), p.lowest);
    EXPECT_EQ(decoded(p.highest_bytes, p.is_signed), p.highest);
}

TEST_P(IntLimitsTest, OnePastEachLimitIsRejected) {
    const Limits& p = GetParam();
    const auto below = encode_int(p.lowest - 1, p.size, p.is_signed);
    ASSERT_FALSE(below.ok());
    EXPECT_NE(below.error().message.find("does not fit"), std::string::npos);
    EXPECT_FALSE(encode_int(p.highest + 1, p.size, p.is_signed).ok());
}

INSTANTIATE_TEST_SUITE_P(
    AllSizes, IntLimitsTest,
    ::testing::Values(
        Limits{1, false, 0, 255, {0x00}, {0xFF}}, Limits{1, true, -128, 127, {0x80}, {0x7F}},
        Limits{2, false, 0, 65535, {0, 0}, {0xFF, 0xFF}},
        Limits{2, true, -32768, 32767, {0x80, 0}, {0x7F, 0xFF}},
        Limits{4, false, 0, 4294967295LL, {0, 0, 0, 0}, {0xFF, 0xFF, 0xFF, 0xFF}},
        Limits{4, true, -2147483648LL, 2147483647, {0x80, 0, 0, 0}, {0x7F, 0xFF, 0xFF, 0xFF}},
        Limits{8, false, 0, kTwo64 - 1, Bytes(8, 0), Bytes(8, 0xFF)},
        Limits{8,
               true,
               -kTwo63,
               kTwo63 - 1,
               {0x80, 0, 0, 0, 0, 0, 0, 0},
               {0x7F, 0xFF, 0xFF, 0xFF, 0xFF, 0xFF, 0xFF, 0xFF}}));

TEST(IntCodec, NegativeOneInTwoBytesIsAllOnes) {
    EXPECT_EQ(encoded(-1, 2, true), (Bytes{0xFF, 0xFF}));
    EXPECT_EQ(decoded({0xFF, 0xFF}, true), -1);
    EXPECT_EQ(decoded({0xFF, 0xFF}, false), 65535);
}

TEST(IntCodec, BigEndianAndAllBytesWritten) {
    EXPECT_EQ(encoded(0x1234, 2, false), (Bytes{0x12, 0x34}));
    EXPECT_EQ(encoded(0x1234, 4, false), (Bytes{0, 0, 0x12, 0x34}));
    EXPECT_EQ(encoded(0x0102030405060708LL, 8, false), (Bytes{1, 2, 3, 4, 5, 6, 7, 8}));
    EXPECT_EQ(encoded(-2, 4, true), (Bytes{0xFF, 0xFF, 0xFF, 0xFE}));
    EXPECT_EQ(encoded(1, 1, true), (Bytes{0x01}));
}

TEST(IntCodec, RoundTripsManyValues) {
    for (std::uint64_t size : {1u, 2u, 4u, 8u}) {
        for (bool is_signed : {false, true}) {
            const WideInt lo = int_lowest(size, is_signed);
            const WideInt hi = int_highest(size, is_signed);
            const WideInt step = (hi - lo) / 997 + 1;
            for (WideInt v = lo; v <= hi - step; v += step) {
                EXPECT_EQ(decoded(encoded(v, size, is_signed), is_signed), v);
            }
        }
    }
}

TEST(IntCodec, InvalidSizesAreErrors) {
    for (std::uint64_t size : {0u, 3u, 5u, 16u}) {
        EXPECT_FALSE(is_valid_int_size(size));
        const auto r = encode_int(0, size, false);
        ASSERT_FALSE(r.ok());
        EXPECT_NE(r.error().message.find("invalid integer size"), std::string::npos);
        EXPECT_FALSE(decode_int(Bytes(size, 0), false).ok());
    }
}

TEST(IntCodec, FormatsDecimal) {
    EXPECT_EQ(format_int(0), "0");
    EXPECT_EQ(format_int(-1), "-1");
    EXPECT_EQ(format_int(kTwo64 - 1), "18446744073709551615");
    EXPECT_EQ(format_int(-kTwo63), "-9223372036854775808");
    const WideInt most_negative =
        -(static_cast<WideInt>((static_cast<unsigned __int128>(1) << 127) - 1)) - 1;
    EXPECT_EQ(format_int(most_negative), "-170141183460469231731687303715884105728");
}

TEST(IntCodec, ParsesDecimalText) {
    EXPECT_EQ(parse_int_text("42").value(), 42);
    EXPECT_EQ(parse_int_text("+5").value(), 5);
    EXPECT_EQ(parse_int_text("-0").value(), 0);
    EXPECT_EQ(parse_int_text("007").value(), 7);
    EXPECT_EQ(parse_int_text("-9223372036854775808").value(), -kTwo63);
    EXPECT_EQ(parse_int_text("18446744073709551615").value(), kTwo64 - 1);
    EXPECT_EQ(parse_int_text("170141183460469231731687303715884105727").value(),
              static_cast<WideInt>((static_cast<unsigned __int128>(1) << 127) - 1));
    EXPECT_EQ(parse_int_text("0000000000000000000000000000000000000000000001").value(), 1);
}

TEST(IntCodec, RejectsNonDecimalText) {
    for (const char* bad : {"", "-", "+", "1.0", " 1", "1 ", "0x10", "1e3", "--1", "12a", "+-1"}) {
        const auto r = parse_int_text(bad);
        ASSERT_FALSE(r.ok()) << bad;
        EXPECT_NE(r.error().message.find("not a decimal integer"), std::string::npos) << bad;
    }
}

TEST(IntCodec, RejectsOutOfRangeText) {
    for (const char* bad :
         {"170141183460469231731687303715884105728", "999999999999999999999999999999999999999",
          "-9999999999999999999999999999999999999999999999999999"}) {
        const auto r = parse_int_text(bad);
        ASSERT_FALSE(r.ok()) << bad;
        EXPECT_NE(r.error().message.find("out of the integer range"), std::string::npos);
    }
}

}  // namespace
}  // namespace olcb::cdi
