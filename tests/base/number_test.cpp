#include "base/number.hpp"

#include <gtest/gtest.h>

namespace olcb::base {
namespace {

TEST(ParseUnsigned, DecimalAndHexAsTyped) {
    EXPECT_EQ(parse_unsigned("251"), 251u);
    EXPECT_EQ(parse_unsigned("0xFB"), 0xFBu);
    EXPECT_EQ(parse_unsigned("0Xfb"), 0xFBu);
    EXPECT_EQ(parse_unsigned("18446744073709551615"), UINT64_MAX);
}

TEST(ParseUnsigned, AnythingElseIsRefused) {
    EXPECT_FALSE(parse_unsigned(""));
    EXPECT_FALSE(parse_unsigned("0x"));
    EXPECT_FALSE(parse_unsigned("-1"));
    EXPECT_FALSE(parse_unsigned("12 "));
    EXPECT_FALSE(parse_unsigned("0xFG"));
    EXPECT_FALSE(parse_unsigned("18446744073709551616"));
}

}  // namespace
}  // namespace olcb::base
